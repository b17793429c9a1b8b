// The first output API, kept as two thin wrappers over output_file.h for code written against
// it; new code declares its outputs in an OutputSet (output_file.h) and streams into them.
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace bluetile {

// Calls write(path of a file to create) and publishes that file at `path` (see output_file.h).
void write_atomically(const std::string& path, const std::function<void(const std::string&)>& write);

// write_output(path, content).
void write_text_atomically(const std::string& path, std::string_view content);

}  // namespace bluetile
