// Reading input files so that a file is never silently cut short: every open and read is
// checked, and running out of memory while reading is an error too (a stream read
// under `ulimit -v` once stopped half-way without a word). "-" is standard input.
#pragma once

#include <functional>
#include <string>
#include <string_view>

namespace bluetile {

// Calls consume(chunk) for each piece of the file in order (64 KiB at most each). Throws
// Error("<path>: <what>"): cannot open, is a folder, a read error. What consume throws (its own
// errors, std::bad_alloc) propagates as it is: the caller knows where it was.
void for_each_chunk(const std::string& path, const std::function<void(std::string_view)>& consume);

// The whole file in memory, with the same errors, and Error("<path>: out of memory after N
// bytes") when it does not fit.
std::string read_input(const std::string& path);

// Opens the FIFO at `path` with `flags`. The open waits until `partner` ("a writer" for an input,
// "a reader" for an output) opens the other end, however long: a second into the wait, one line
// on stderr says so ("bluetile: PATH: waiting for a writer to open this FIFO") instead of a
// silent hang. Returns what open() returns, errno kept.
int open_fifo_saying_so(const std::string& path, int flags, const char* partner);

}  // namespace bluetile
