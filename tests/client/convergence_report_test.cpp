// `--report DIR`: the CSV, the gnuplot script with the fits in its header, and the plots
// gnuplot draws from them.
#include "client/convergence_report.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "tests/support/test_env.h"

namespace pf {
namespace {

std::vector<ConvergencePoint> PowerLawLog(bool with_reference) {
    std::vector<ConvergencePoint> points;
    for (uint64_t epoch = 1; epoch <= 30; ++epoch) {
        ConvergencePoint point;
        point.epochs = epoch;
        point.photons = epoch << 16;
        point.seconds = 0.1 + 0.05 * static_cast<double>(epoch);
        point.pixels = 1024;
        const double n = static_cast<double>(point.photons);
        if (epoch >= 2) point.estimated = ErrorEstimate{true, std::pow(n, -0.5), std::pow(n, -1.0)};
        if (with_reference)
            point.measured = ImageDifference{2 * std::pow(n, -1.0 / 3.0), std::pow(n, -0.6)};
        points.push_back(point);
    }
    return points;
}

std::string Slurp(const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

TEST(ConvergenceReportTest, ScriptHeaderCarriesTheFitsAndAQuotedTitle) {
    const std::string script = ConvergencePlotScript("my_scene \"v2\".gltf", PowerLawLog(true));
    EXPECT_NE(script.find("title = \"my\\\\_scene \\\"v2\\\".gltf\"\n"), std::string::npos)
        << script;
    EXPECT_NE(script.find("has_reference = 1\n"), std::string::npos);
    EXPECT_NE(script.find("est_n_ok = 1\nest_n_slope = -0.5\n"), std::string::npos);
    EXPECT_NE(script.find("ref_n_ok = 1\nref_n_slope = -0.333333333\n"), std::string::npos);
    const std::string without = ConvergencePlotScript("x", PowerLawLog(false));
    EXPECT_NE(without.find("has_reference = 0\n"), std::string::npos);
    EXPECT_NE(without.find("ref_t_ok = 0\n"), std::string::npos);
}

TEST(ConvergenceReportTest, WritesCsvScriptAndPlotsThroughGnuplot) {
    const std::filesystem::path dir = testing::FreshTempDir("convergence-report");
    ASSERT_TRUE(PrepareReportDir(dir.string()).ok());
    for (const bool with_reference : {false, true}) {
        const absl::Status status =
            WriteConvergenceReport(dir.string(), "cornell-box.gltf", PowerLawLog(with_reference));
        ASSERT_TRUE(status.ok()) << status;  // gnuplot-nox is a dependency (deploy/install-deps.sh)
        const std::string csv = Slurp(dir / "convergence.csv");
        EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 31);
        const std::string png = Slurp(dir / "convergence.png");
        ASSERT_GT(png.size(), 8u);
        EXPECT_EQ(png.substr(1, 3), "PNG");
        const std::string svg = Slurp(dir / "convergence.svg");
        EXPECT_NE(svg.find("<svg"), std::string::npos);
        EXPECT_NE(svg.find("slope -0.500"), std::string::npos);
        EXPECT_EQ(svg.find("slope -0.333") != std::string::npos, with_reference);
    }
    std::filesystem::remove_all(dir);
}

TEST(ConvergenceReportTest, ALogWithNoErrorYetWritesTheCsvAndNoPlot) {
    // One epoch and no reference: no error is known, which is no failure (gnuplot's log axes
    // would have nothing to span).
    const std::filesystem::path dir = testing::FreshTempDir("convergence-report-early");
    ASSERT_TRUE(PrepareReportDir(dir.string()).ok());
    ConvergencePoint first;
    first.seconds = 0.3;
    first.epochs = 1;
    first.photons = 1 << 18;
    const std::vector<ConvergencePoint> points = {first};
    const absl::Status status = WriteConvergenceReport(dir.string(), "cornell-box.gltf", points);
    ASSERT_TRUE(status.ok()) << status;
    EXPECT_TRUE(std::filesystem::exists(dir / "convergence.csv"));
    EXPECT_FALSE(std::filesystem::exists(dir / "convergence.png"));
    std::filesystem::remove_all(dir);
}

TEST(ConvergenceReportTest, UnwritableFolderIsNamed) {
    const absl::Status status = PrepareReportDir("/proc/pf-no-such-report");
    ASSERT_FALSE(status.ok());
    EXPECT_NE(status.message().find("/proc/pf-no-such-report"), std::string::npos);
}

}  // namespace
}  // namespace pf
