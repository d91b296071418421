#pragma once
// One campaign at a time per output folder: an advisory lock (flock) on {out}/campaign.lock,
// which holds the holder's pid and start time while it runs and is emptied when it ends. The
// kernel drops the lock when its holder dies, so a non-empty file found unlocked is the trace
// of a campaign that was killed: it is reported (stale_note) and taken over.
//
// The lock also lists the process groups of the steps that run ("step group PGID started
// TICKS", one line each, TICKS the leader's start time from /proc/PID/stat; kept current by
// add_step_group/remove_step_group). A step dies with its runner (step_process.hpp), but not at
// once (a fit finishes its iteration and saves its checkpoint), so a takeover first waits for
// the groups the stale lock lists: up to `wait_for_steps`, then SIGTERM, and SIGKILL after
// `wait_for_steps` more. A group counts as the stale campaign's while its leader (pid = group
// id) has the recorded start time, or is gone and the group lives on in its children; a group
// id the system has given to another process meanwhile is left alone.
#include <sys/types.h>

#include <chrono>
#include <filesystem>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace dtwire::app {

class CampaignLock {
 public:
  // Throws InputError naming the lock file, the holder's pid and start time if another
  // campaign holds the folder. Reports on stderr which stale step groups it waits for.
  explicit CampaignLock(const std::filesystem::path& out,
                        std::chrono::seconds wait_for_steps = std::chrono::seconds(30));
  ~CampaignLock();
  CampaignLock(const CampaignLock&) = delete;
  CampaignLock& operator=(const CampaignLock&) = delete;

  // "" or what the stale lock said (pid and start time of the campaign that did not finish).
  const std::string& stale_note() const { return stale_note_; }

  // Thread-safe and never throw; rewrite the lock file's list of step groups (a lock that
  // cannot be written, on a full disk, leaves the steps to die with the runner alone).
  void add_step_group(pid_t group);
  void remove_step_group(pid_t group);

 private:
  bool write_contents();

  int fd_ = -1;
  std::string path_;
  std::string stale_note_;
  std::string holder_;  // "pid N, started T"
  std::mutex mutex_;
  std::set<std::pair<pid_t, unsigned long long>> groups_;
};

struct StepGroup {
  pid_t group = 0;
  unsigned long long start_ticks = 0;  // the leader's start time, clock ticks after boot
};

// The step groups a lock's text lists ("step group PGID started TICKS" lines).
std::vector<StepGroup> listed_step_groups(const std::string& lock_text);

// The start time of a process (field 22 of /proc/PID/stat), 0 if it does not run.
unsigned long long process_start_ticks(pid_t pid);

// Whether a process of the group still runs and the group is the one recorded (see above).
bool step_group_alive(const StepGroup& group);

// Waits until none of `groups` runs: up to `grace`, then SIGTERM to those left, SIGKILL after
// `grace` more. Returns the groups that had to be signalled.
std::vector<pid_t> stop_step_groups(const std::vector<StepGroup>& groups, std::chrono::seconds grace);

}  // namespace dtwire::app
