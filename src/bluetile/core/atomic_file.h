// Writing output files so that a failed run leaves nothing half-written: everything goes to a
// temporary file beside the target, which is renamed over the target only once complete.
#pragma once

#include <functional>
#include <string>

namespace bluetile {

// Calls write(temporary_path), then renames the temporary file to `path`. The temporary path
// keeps the target's extension (image writers choose the format by it). If write throws, the
// temporary file is removed and the exception propagates; `path` is untouched.
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

// Same, for text: the content is produced into a string first.
void write_text_atomically(const std::string& path, const std::string& content);

}  // namespace bluetile
