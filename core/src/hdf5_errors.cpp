#include "hdf5_errors.hpp"

namespace dtwire {

Hdf5ErrorsSilenced::Hdf5ErrorsSilenced() {
  H5Eget_auto2(H5E_DEFAULT, &handler_, &data_);
  H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
}

Hdf5ErrorsSilenced::~Hdf5ErrorsSilenced() { H5Eset_auto2(H5E_DEFAULT, handler_, data_); }

namespace {

extern "C" herr_t append_record(unsigned, const H5E_error2_t* record, void* text_pointer) {
  auto& text = *static_cast<std::string*>(text_pointer);
  std::string line = std::string(record->func_name ? record->func_name : "?") + ": " +
                     (record->desc && *record->desc ? record->desc : "error");
  char minor[128] = "";
  if (H5Eget_msg(record->min_num, nullptr, minor, sizeof minor) > 0 && line.find(minor) == std::string::npos)
    line += " (" + std::string(minor) + ")";
  text += (text.empty() ? "" : "; ") + line;
  return 0;
}

}  // namespace

std::string hdf5_error_text() {
  std::string text;
  // Upward: from the function where the error arose (a system call's errno) to the API call.
  H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, append_record, &text);
  H5Eclear2(H5E_DEFAULT);
  return text;
}

}  // namespace dtwire
