// Checkpoint files: "PFJOB1\n", the record's length (8 bytes) and the record, then the
// estimate's state; the checksum trailer of WriteChecksummedFile after them.
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

constexpr std::string_view kMagic = "PFJOB1\n";
constexpr std::string_view kPrefix = "checkpoint-";
constexpr std::string_view kSuffix = ".pfc";
constexpr size_t kKept = 2;

absl::StatusOr<JobCheckpointData> Decode(const std::string& bytes, const std::string& path) {
    const auto corrupt = [&](const std::string& what) {
        return absl::DataLossError(absl::StrCat(path, ": ", what));
    };
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

absl::Status CheckpointStore::Write(const JobCheckpointData& checkpoint) const {
    const std::string job_dir = JobDir(checkpoint.record.job_id());
    std::error_code error;
    fs::create_directories(job_dir, error);
    if (error)
        return absl::UnavailableError(absl::StrCat(job_dir, ": cannot create: ", error.message()));
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

std::vector<JobCheckpointData> CheckpointStore::ReadAll() const {
    std::vector<JobCheckpointData> jobs;
    std::error_code error;
    for (const fs::directory_entry& entry : fs::directory_iterator(dir_, error)) {
        if (!entry.is_directory()) continue;
        const std::string job_id = entry.path().filename().string();
        std::vector<fs::path> files = CheckpointFiles(entry.path());
        bool found = false;
        for (auto file = files.rbegin(); file != files.rend() && !found; ++file) {
            absl::StatusOr<std::string> bytes = ReadChecksummedFile(file->string());
            absl::StatusOr<JobCheckpointData> checkpoint =
                bytes.ok() ? Decode(*bytes, file->string())
                           : absl::StatusOr<JobCheckpointData>(bytes.status());
            if (checkpoint.ok() && checkpoint->record.job_id() != job_id)
                checkpoint = absl::DataLossError(
                    absl::StrCat(file->string(), ": holds job ", checkpoint->record.job_id()));
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
