#pragma once
// The committed state of a contact part as a flat list of doubles, for checkpoints: each part
// writes and reads its own fields (so a checkpoint cannot drop one), and the doubles are stored
// exactly, so that a resumed run repeats the uninterrupted one bit for bit.
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include "contact_kernel.hpp"

namespace dtwire::fem::contact {

class StateWriter {
 public:
  void put(double value) { values_.push_back(value); }
  void put(const Vector3& v) {
    for (unsigned c = 0; c < 3; ++c) values_.push_back(v[c]);
  }
  std::vector<double> take() { return std::move(values_); }

 private:
  std::vector<double> values_;
};

// Reads what a StateWriter wrote; `owner` names the part in the error when the sizes differ
// (a checkpoint of another mesh or contact set-up).
class StateReader {
 public:
  StateReader(const std::vector<double>& values, std::string owner) : values_(values), owner_(std::move(owner)) {}
  double get() {
    if (next_ >= values_.size()) mismatch();
    const double v = values_[next_++];
    if (!std::isfinite(v)) throw std::invalid_argument("the " + owner_ + " state holds a value that is not finite");
    return v;
  }
  Vector3 get_vector() {
    Vector3 v;
    for (unsigned c = 0; c < 3; ++c) v[c] = get();
    return v;
  }
  // A whole number in [lowest, highest] (a count or an index), checked: the file may be damaged.
  long get_whole(long lowest, long highest) {
    const double v = get();
    if (!(v >= static_cast<double>(lowest) && v <= static_cast<double>(highest) && v == std::floor(v))) mismatch();
    return static_cast<long>(v);
  }
  void finish() const {
    if (next_ != values_.size()) mismatch();
  }

 private:
  [[noreturn]] void mismatch() const {
    throw std::invalid_argument("the " + owner_ + " state holds " + std::to_string(values_.size()) +
                                " values, not what this run's set-up needs");
  }
  const std::vector<double>& values_;
  std::string owner_;
  std::size_t next_ = 0;
};

}  // namespace dtwire::fem::contact
