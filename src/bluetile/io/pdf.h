// PDF output of vector drawings through cairo (cairographics.org), one page per document.
//
// cairo is opened at run time (libcairo.so.2, on first use) rather than linked: it pulls in
// fontconfig, freetype, pixman and the X libraries, which no other command needs to load, and
// the library's core stays free of it. Its header is needed at build time (libcairo2-dev);
// without it, or without the library at run time, write_pdf throws an Error saying so.
// Text uses the fonts fontconfig finds for "DejaVu Sans" (embedded as subsets).
#pragma once

#include <string>

#include "bluetile/core/output_file.h"
#include "bluetile/io/svg.h"

namespace bluetile {

// Writes `document` as a one-page PDF whose page is the document's display size (converted to
// points: px = 0.75 pt, mm, cm, in), through output_file.h (cairo writes a file: the staged one,
// or a private temporary copied to a device). Throws Error naming the path on failure.
void write_pdf(const SvgDocument& document, OutputFile& out);
void write_pdf(const SvgDocument& document, const std::string& path);

// Why write_pdf cannot work here (cairo missing at build time, or not loadable now), or ""
// when it can: for checking before any work is done.
std::string pdf_unavailable_reason();

}  // namespace bluetile
