// Where a coordinator keeps its jobs' checkpoints: one folder per job under the checkpoint
// folder, holding its latest two checkpoint files (checkpoint-SEQUENCE.pfc) and the parts of
// the job that never change (KIND-SHA256.fixed: the scene bundle, a ppm job's hit points),
// each written once and named by every checkpoint that needs it. Every file is written whole
// or not at all and checked when read (core/util/file_io.h); a fixed part must also match the
// SHA-256 its checkpoint names. A checkpoint that fails a check is reported, naming the file,
// and the one before it used. Not thread-safe: one writer per folder.
#pragma once

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "photonfarm/v1/checkpoint.pb.h"
#include "wire/blob_codec.h"

namespace pf {

// One checkpoint: the job's record, its estimate's state (Estimate::Save, without its fixed
// part) and the contents of the fixed parts the record names (record.fixed_parts), by kind.
struct JobCheckpointData {
    photonfarm::v1::JobCheckpoint record;
    std::string estimate;
    std::map<std::string, std::shared_ptr<const Blob>> fixed;
};

class CheckpointStore {
public:
    explicit CheckpointStore(std::string dir) : dir_(std::move(dir)) {}
    const std::string& Dir() const { return dir_; }

    // Writes the fixed parts the record names whose files are not there yet, then the job's
    // checkpoint (record.sequence names the file), and removes all but the latest two
    // checkpoints. UNAVAILABLE naming the file when one cannot be written; INTERNAL when the
    // record names a part that `fixed` lacks, or by a name unfit for a file.
    absl::Status Write(const JobCheckpointData& checkpoint) const;
    // One checkpoint file with its fixed parts. DATA_LOSS naming the file that is truncated,
    // corrupt, missing (a fixed part) or altered (a fixed part whose SHA-256 differs from the
    // one the checkpoint names).
    absl::StatusOr<JobCheckpointData> Read(const std::string& path) const;
    // The latest good checkpoint of every job in the folder. Checkpoints that fail their
    // checks are logged (Read's error) and skipped for the one before.
    std::vector<JobCheckpointData> ReadAll() const;
    // Forgets a job: its folder goes, fixed parts included.
    void Remove(const std::string& job_id) const;

    // Where a job's fixed part is kept.
    std::string FixedPartPath(const std::string& job_id,
                              const photonfarm::v1::FixedPart& part) const;

private:
    std::string JobDir(const std::string& job_id) const;

    std::string dir_;
};

}  // namespace pf
