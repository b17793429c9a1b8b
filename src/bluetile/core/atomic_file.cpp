#include "bluetile/core/atomic_file.h"

#include "bluetile/core/output_file.h"

namespace bluetile {

void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  OutputSet outputs;
  outputs.add(path).write_through_path(write);
  outputs.publish();
}

void write_text_atomically(const std::string& path, std::string_view content) { write_output(path, content); }

}  // namespace bluetile
