#include "bench_args.h"

#include <cstdio>
#include <exception>
#include <new>

namespace bluetile::bench {
namespace {

// One line, whatever the message held.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n' || c == '\r') c = ' ';
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

// CLI11's own parse errors in our words: an argument it did not expect ("The following
// argument(s) was/were not expected: a b"), an option without its value ("--sizes: 1 required
// INT missing") or given twice ("--repeats: At Most 1 required but received 2"); other errors
// keep CLI11's text.
std::string parse_error_text(const CLI::ParseError& e) {
  std::string text = one_line(e.what());
  if (dynamic_cast<const BadArgument*>(&e)) return text;
  if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
    const std::size_t colon = text.find(": ");
    std::string first = colon == std::string::npos ? text : text.substr(colon + 2);
    first = first.substr(0, first.find(' '));
    if (!first.empty() && first[0] == '-') return "unknown option '" + first + "' (see --help)";
    return "unexpected argument '" + first + "' (see --help)";
  }
  if (dynamic_cast<const CLI::ArgumentMismatch*>(&e)) {
    const std::string option = text.substr(0, text.find(':'));
    if (text.ends_with(" missing")) return option + ": missing value (see --help)";
    if (text.find("required but received") != std::string::npos) return option + ": given more than once (see --help)";
  }
  return text + " (see --help)";
}

}  // namespace

BadArgument bad_argument(const std::string& option, const std::string& value, const std::string& expected) {
  return BadArgument(option + " '" + value + "': " + expected);
}

std::int64_t signed_integer(const std::string& option, const std::string& text, std::int64_t min, std::int64_t max) {
  cli::WholeNumber value;
  const std::string problem = cli::check_integer(text, cli::whole(min), cli::whole(max), value);
  if (!problem.empty()) throw bad_argument(option, text, problem);
  return value.negative ? -static_cast<std::int64_t>(value.magnitude - 1) - 1 : static_cast<std::int64_t>(value.magnitude);
}

std::uint64_t unsigned_integer(const std::string& option, const std::string& text, std::uint64_t min, std::uint64_t max) {
  cli::WholeNumber value;
  const std::string problem = cli::check_integer(text, cli::whole(min), cli::whole(max), value);
  if (!problem.empty()) throw bad_argument(option, text, problem);
  return value.magnitude;
}

double real_argument(const std::string& option, const std::string& text, RealRange range) {
  double value = 0.0;
  const std::string problem = cli::check_real(text, range, value);
  if (!problem.empty()) throw bad_argument(option, text, problem);
  return value;
}

const std::string& name_argument(const std::string& option, const std::string& text, const std::vector<std::string>& accepted) {
  for (const std::string& name : accepted)
    if (name == text) return name;
  throw bad_argument(option, text, "unknown name; expected one of " + joined(accepted, ", "));
}

std::string option_name(const std::string& names) { return cli::message_name(names); }

std::string joined(const std::vector<std::string>& values, const std::string& separator) {
  std::string text;
  for (const std::string& v : values) text += (text.empty() ? "" : separator) + v;
  return text;
}

CLI::Option* add_real(CLI::App& app, const std::string& names, double& target, RealRange range, const std::string& help) {
  const std::string name = option_name(names);
  return app
      .add_option_function<std::string>(
          names, [&target, name, range](const std::string& text) { target = real_argument(name, text, range); }, help)
      ->type_name("NUMBER")
      ->default_str(number_text(target));
}

CLI::Option* add_reals(CLI::App& app, const std::string& names, std::vector<double>& target, RealRange range,
                       const std::string& help) {
  const std::string name = option_name(names);
  return app
      .add_option_function<std::vector<std::string>>(
          names,
          [&target, name, range](const std::vector<std::string>& texts) {
            target.clear();
            for (const std::string& text : texts) target.push_back(real_argument(name, text, range));
          },
          help)
      ->type_name("NUMBER")
      ->default_str(joined_numbers(target));
}

CLI::Option* add_name(CLI::App& app, const std::string& names, std::string& target, std::vector<std::string> accepted,
                      const std::string& help) {
  const std::string name = option_name(names);
  const std::string type = joined(accepted, "|");
  return app
      .add_option_function<std::string>(
          names,
          [&target, name, accepted = std::move(accepted)](const std::string& text) {
            target = name_argument(name, text, accepted);
          },
          help)
      ->type_name(type)
      ->default_str(target);
}

CLI::Option* add_names(CLI::App& app, const std::string& names, std::vector<std::string>& target,
                       std::vector<std::string> accepted, const std::string& help) {
  const std::string name = option_name(names);
  const std::string type = joined(accepted, "|");
  return app
      .add_option_function<std::vector<std::string>>(
          names,
          [&target, name, accepted = std::move(accepted)](const std::vector<std::string>& texts) {
            target.clear();
            for (const std::string& text : texts) target.push_back(name_argument(name, text, accepted));
          },
          help)
      ->type_name(type)
      ->default_str(joined(target));
}

std::string given(const CLI::Option* option) { return joined(option->results()); }

void check_given(const CLI::Option* option, bool allowed, const std::string& expected) {
  if (option->count() == 0 || allowed) return;
  const std::string name = option_name(option->get_name());
  if (option->get_type_size_max() == 0) throw BadArgument(name + ": " + expected);  // a flag: no value to quote
  throw bad_argument(name, given(option), expected);
}

bool parse(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    app.exit(e);
    return false;
  } catch (const CLI::CallForAllHelp& e) {
    app.exit(e);
    return false;
  }
  return true;
}

int exit_status(const char* program) {
  try {
    throw;
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: %s\n", program, parse_error_text(e).c_str());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "%s: out of memory\n", program);
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program, one_line(e.what()).c_str());
    return 1;
  } catch (...) {
    std::fprintf(stderr, "%s: unknown error\n", program);
    return 1;
  }
}

}  // namespace bluetile::bench
