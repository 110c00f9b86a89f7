// Where a coordinator keeps its jobs' checkpoints: one folder per job under the checkpoint
// folder, holding its latest two checkpoint files (checkpoint-SEQUENCE.pfc), each written
// whole or not at all and checked when read (core/util/file_io.h). A file that fails its
// check is reported and the one before it used. Not thread-safe: one writer per folder.
#pragma once

#include <string>
#include <vector>

#include "absl/status/statusor.h"
#include "photonfarm/v1/checkpoint.pb.h"

namespace pf {

// One checkpoint: the job's record and its estimate's state (ProgressiveEstimate::Save).
struct JobCheckpointData {
    photonfarm::v1::JobCheckpoint record;
    std::string estimate;
};

class CheckpointStore {
public:
    explicit CheckpointStore(std::string dir) : dir_(std::move(dir)) {}
    const std::string& Dir() const { return dir_; }

    // Writes the job's checkpoint (record.sequence names the file) and removes all but the
    // latest two. UNAVAILABLE naming the file when it cannot be written.
    absl::Status Write(const JobCheckpointData& checkpoint) const;
    // The latest good checkpoint of every job in the folder. Files that fail their checks are
    // logged (naming the file and what is wrong) and skipped for the one before.
    std::vector<JobCheckpointData> ReadAll() const;
    // Forgets a job: its folder goes.
    void Remove(const std::string& job_id) const;

private:
    std::string JobDir(const std::string& job_id) const;

    std::string dir_;
};

}  // namespace pf
