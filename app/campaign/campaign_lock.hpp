#pragma once
// One campaign at a time per output folder: an advisory lock (flock) on {out}/campaign.lock,
// which holds the holder's pid and start time while it runs and is emptied when it ends. The
// kernel drops the lock when its holder dies, so a non-empty file found unlocked is the trace
// of a campaign that was killed: it is reported (stale_note) and taken over.
#include <filesystem>
#include <string>

namespace dtwire::app {

class CampaignLock {
 public:
  // Throws InputError naming the lock file, the holder's pid and start time if another
  // campaign holds the folder.
  explicit CampaignLock(const std::filesystem::path& out);
  ~CampaignLock();
  CampaignLock(const CampaignLock&) = delete;
  CampaignLock& operator=(const CampaignLock&) = delete;

  // "" or what the stale lock said (pid and start time of the campaign that did not finish).
  const std::string& stale_note() const { return stale_note_; }

 private:
  int fd_ = -1;
  std::string stale_note_;
};

}  // namespace dtwire::app
