// Checkpoint files: "PFJOB2\n", the record's length (8 bytes) and the record, then the
// estimate's state; fixed parts: their contents. Both end in the checksum trailer of
// WriteChecksummedFile.
#include "server/checkpoint_store.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <system_error>

#include "absl/strings/str_cat.h"
#include "absl/strings/str_format.h"
#include "core/util/file_io.h"

namespace pf {
namespace {

namespace fs = std::filesystem;

// 2: the scene and a ppm job's hit points kept apart (fixed parts), the estimate packed.
constexpr std::string_view kMagic = "PFJOB2\n";
constexpr std::string_view kEarlierMagic = "PFJOB1\n";
constexpr std::string_view kPrefix = "checkpoint-";
constexpr std::string_view kSuffix = ".pfc";
constexpr char kFixedSuffix[] = ".fixed";
constexpr size_t kKept = 2;

absl::StatusOr<JobCheckpointData> Decode(const std::string& bytes, const std::string& path) {
    const auto corrupt = [&](const std::string& what) {
        return absl::DataLossError(absl::StrCat(path, ": ", what));
    };
    if (std::string_view(bytes).starts_with(kEarlierMagic))
        return corrupt(
            "a checkpoint of an earlier format (PFJOB1), which this build does not read");
    if (!std::string_view(bytes).starts_with(kMagic)) return corrupt("not a photonfarm checkpoint");
    uint64_t length = 0;
    if (bytes.size() < kMagic.size() + sizeof(length)) return corrupt("truncated");
    std::memcpy(&length, bytes.data() + kMagic.size(), sizeof(length));
    const size_t start = kMagic.size() + sizeof(length);
    if (length > bytes.size() - start) return corrupt("truncated record");
    JobCheckpointData checkpoint;
    if (!checkpoint.record.ParseFromArray(bytes.data() + start, static_cast<int>(length)))
        return corrupt("unreadable record");
    checkpoint.estimate = bytes.substr(start + length);
    return checkpoint;
}

// A fixed part's kind and digest become a file name: lowercase letters and dashes, and 64
// lowercase hex digits, so that no record can name a file outside its job's folder.
bool FitForAName(const photonfarm::v1::FixedPart& part) {
    const auto all_of = [](std::string_view text, auto fits) {
        return std::all_of(text.begin(), text.end(), fits);
    };
    return !part.kind().empty() && part.kind().size() <= 32 &&
           all_of(part.kind(), [](char c) { return (c >= 'a' && c <= 'z') || c == '-'; }) &&
           part.sha256().size() == 64 && all_of(part.sha256(), [](char c) {
               return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f');
           });
}

// The job's checkpoint files, oldest first.
std::vector<fs::path> CheckpointFiles(const fs::path& job_dir) {
    std::vector<fs::path> files;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(job_dir, error)) {
        const std::string name = entry.path().filename().string();
        if (entry.is_regular_file() && name.starts_with(kPrefix) && name.ends_with(kSuffix))
            files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());  // fixed-width sequence numbers sort as text
    return files;
}

}  // namespace

std::string CheckpointStore::JobDir(const std::string& job_id) const {
    return (fs::path(dir_) / job_id).string();
}

std::string CheckpointStore::FixedPartPath(const std::string& job_id,
                                           const photonfarm::v1::FixedPart& part) const {
    return (fs::path(JobDir(job_id)) / absl::StrCat(part.kind(), "-", part.sha256(), kFixedSuffix))
        .string();
}

absl::Status CheckpointStore::Write(const JobCheckpointData& checkpoint) const {
    const std::string& job_id = checkpoint.record.job_id();
    const std::string job_dir = JobDir(job_id);
    std::error_code error;
    fs::create_directories(job_dir, error);
    if (error)
        return absl::UnavailableError(absl::StrCat(job_dir, ": cannot create: ", error.message()));
    // The parts first: a checkpoint on disk never names a file that is not.
    for (const photonfarm::v1::FixedPart& part : checkpoint.record.fixed_parts()) {
        const auto blob = checkpoint.fixed.find(part.kind());
        if (!FitForAName(part) || blob == checkpoint.fixed.end() ||
            blob->second->digest != part.sha256())
            return absl::InternalError(absl::StrCat("job ", job_id, ": fixed part '", part.kind(),
                                                    "' not given or not as named"));
        const std::string path = FixedPartPath(job_id, part);
        if (fs::exists(path, error)) continue;  // written by an earlier checkpoint: the same bytes
        if (absl::Status status = WriteChecksummedFile(path, {blob->second->bytes}); !status.ok())
            return status;
    }
    const std::string path =
        (fs::path(job_dir) /
         absl::StrFormat("%s%012d%s", kPrefix, checkpoint.record.sequence(), kSuffix))
            .string();
    const std::string record = checkpoint.record.SerializeAsString();
    const uint64_t length = record.size();
    const std::string_view length_bytes(reinterpret_cast<const char*>(&length), sizeof(length));
    if (absl::Status status =
            WriteChecksummedFile(path, {kMagic, length_bytes, record, checkpoint.estimate});
        !status.ok())
        return status;
    std::vector<fs::path> files = CheckpointFiles(job_dir);
    for (size_t i = 0; i + kKept < files.size(); ++i) fs::remove(files[i], error);
    return absl::OkStatus();
}

absl::StatusOr<JobCheckpointData> CheckpointStore::Read(const std::string& path) const {
    absl::StatusOr<std::string> bytes = ReadChecksummedFile(path);
    if (!bytes.ok()) return bytes.status();
    absl::StatusOr<JobCheckpointData> checkpoint = Decode(*bytes, path);
    if (!checkpoint.ok()) return checkpoint.status();
    const std::string& job_id = checkpoint->record.job_id();
    if (job_id != fs::path(path).parent_path().filename().string())
        return absl::DataLossError(absl::StrCat(path, ": holds job ", job_id));
    for (const photonfarm::v1::FixedPart& part : checkpoint->record.fixed_parts()) {
        if (!FitForAName(part) || checkpoint->fixed.contains(part.kind()))
            return absl::DataLossError(
                absl::StrCat(path, ": names a fixed part twice or by a name unfit for a file"));
        const std::string part_path = FixedPartPath(job_id, part);
        absl::StatusOr<std::string> part_bytes = ReadChecksummedFile(part_path);
        if (absl::IsNotFound(part_bytes.status()))
            return absl::DataLossError(absl::StrCat(part_path, ": missing (", path, " needs it)"));
        if (!part_bytes.ok()) return part_bytes.status();
        Blob blob = Blob::Of(std::move(*part_bytes));
        if (blob.digest != part.sha256())
            return absl::DataLossError(absl::StrCat(part_path, ": altered: its SHA-256 is ",
                                                    blob.digest, ", ", path, " names ",
                                                    part.sha256()));
        checkpoint->fixed[part.kind()] = std::make_shared<const Blob>(std::move(blob));
    }
    return checkpoint;
}

std::vector<JobCheckpointData> CheckpointStore::ReadAll() const {
    std::vector<JobCheckpointData> jobs;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir_, error)) {
        if (!entry.is_directory()) continue;
        const std::string job_id = entry.path().filename().string();
        std::vector<fs::path> files = CheckpointFiles(entry.path());
        bool found = false;
        for (auto file = files.rbegin(); file != files.rend() && !found; ++file) {
            absl::StatusOr<JobCheckpointData> checkpoint = Read(file->string());
            if (!checkpoint.ok()) {
                spdlog::error("checkpoint {}{}", std::string(checkpoint.status().message()),
                              std::next(file) != files.rend() ? "; using the one before it" : "");
                continue;
            }
            jobs.push_back(std::move(*checkpoint));
            found = true;
        }
        if (!found && !files.empty())
            spdlog::error("job {}: no readable checkpoint in {}; not resumed", job_id,
                          entry.path().string());
    }
    if (error && error != std::errc::no_such_file_or_directory)
        spdlog::error("checkpoints in {}: {}", dir_, error.message());
    return jobs;
}

void CheckpointStore::Remove(const std::string& job_id) const {
    std::error_code error;
    fs::remove_all(JobDir(job_id), error);
    if (error) spdlog::warn("checkpoints of job {}: cannot remove: {}", job_id, error.message());
}

}  // namespace pf
