#pragma once
// Results that failed validation, by job, until the job is settled: another
// worker's result for it passes (then each failure counts against its
// worker: the fault was theirs), or every worker that could take it failed
// it (then none does: the fault is the job's, or the path's, and the master
// renders it). At most kMaxJobs jobs are remembered.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace igi {

class JobFailures {
 public:
  static constexpr size_t kMaxJobs = 4096;

  // `identity`'s result for the job failed: `name` (its log name) and why.
  void add(uint64_t job_id, const std::string& identity, const std::string& name, const std::string& error) {
    if (jobs_.size() >= kMaxJobs) jobs_.clear();  // jobs long done or cancelled
    Job& job = jobs_[job_id];
    job.workers.push_back(identity);
    job.text += (job.text.empty() ? "" : ", ") + name + " (" + error + ")";
  }
  // Another worker's result passed: the identities of those that failed it.
  std::vector<std::string> take_workers(uint64_t job_id) {
    auto it = jobs_.find(job_id);
    if (it == jobs_.end()) return {};
    std::vector<std::string> workers = std::move(it->second.workers);
    jobs_.erase(it);
    return workers;
  }
  // No worker's result passed: "worker-1 (why), worker-2 (why)", or `otherwise` when none was kept.
  std::string take_text(uint64_t job_id, const std::string& otherwise) {
    auto it = jobs_.find(job_id);
    if (it == jobs_.end()) return otherwise;
    std::string text = std::move(it->second.text);
    jobs_.erase(it);
    return text;
  }

 private:
  struct Job {
    std::vector<std::string> workers;  // identities
    std::string text;                  // what the log names
  };
  std::map<uint64_t, Job> jobs_;
};

}  // namespace igi
