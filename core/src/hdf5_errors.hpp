#pragma once
// HDF5's error stack as text for the user's message. HDF5 reports a failure by a negative return
// value and a stack of (function, description) records; its default handler prints that stack to
// stderr. While an Hdf5ErrorsSilenced lives, nothing is printed and the caller turns the stack
// into an exception's message (hdf5_error_text), which names the file and, for a system call,
// the system's reason (errno and its text, as HDF5's file driver records them).
#include <hdf5.h>

#include <string>

namespace dtwire {

class Hdf5ErrorsSilenced {
 public:
  Hdf5ErrorsSilenced();
  ~Hdf5ErrorsSilenced();
  Hdf5ErrorsSilenced(const Hdf5ErrorsSilenced&) = delete;
  Hdf5ErrorsSilenced& operator=(const Hdf5ErrorsSilenced&) = delete;

 private:
  H5E_auto2_t handler_ = nullptr;
  void* data_ = nullptr;
};

// The current thread's error stack, innermost record first ("H5FD_sec2_open: unable to open
// file: name = 'x', errno = 2, error message = 'No such file or directory'; ..."), then clears
// it. "" if the stack is empty.
std::string hdf5_error_text();

}  // namespace dtwire
