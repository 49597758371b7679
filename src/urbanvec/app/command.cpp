#include "urbanvec/app/command.hpp"

#include <cpl_conv.h>
#include <cpl_string.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "urbanvec/core/error.hpp"
#include "urbanvec/core/version.hpp"
#include "urbanvec/io/atomic_output.hpp"
#include "urbanvec/io/gdal_init.hpp"

namespace urbanvec::app {

namespace {

struct Registered {
  CommandSpec spec;
  CommandFunction run;
};

std::vector<Registered>& registry() {
  static std::vector<Registered> commands;
  return commands;
}

const Registered* findCommand(const std::string& name) {
  for (const Registered& r : registry())
    if (r.spec.name == name) return &r;
  return nullptr;
}

std::atomic<bool> gInterrupted{false};
extern "C" void onSignal(int) {
  gInterrupted = true;
}

/// Options every subcommand accepts, handled here rather than by the subcommand.
std::vector<OptionSpec> commonOptions() {
  std::vector<OptionSpec> o;
  o.push_back(option("-q", ValueType::Flag, "", "Quiet: print no progress."));
  o.push_back(option("-progress", ValueType::Choice, "<gdal|lines|none>",
                     "Progress style: GDAL's dotted line, one 'PROGRESS <percent> <stage>' line per "
                     "update (for scripts and the QGIS plugin), or none.")
                  .oneOf({"gdal", "lines", "none"})
                  .byDefault("gdal"));
  o.push_back(option("--config", ValueType::String, "<key> <value>", "Sets a GDAL configuration option.")
                  .values(2)
                  .many());
  return o;
}

bool looksLikeOption(const std::string& a) {
  return a.size() >= 2 && a[0] == '-' && (std::isalpha(static_cast<unsigned char>(a[1])) || a[1] == '-');
}

std::string normalise(const std::string& a) {
  // GDAL accepts both -name and --name; keep one dash except for --config.
  if (a.rfind("--", 0) == 0 && a != "--config") return a.substr(1);
  return a;
}

const OptionSpec* findOption(const std::vector<OptionSpec>& specs, const std::string& name) {
  for (const OptionSpec& s : specs)
    if (s.name == name) return &s;
  return nullptr;
}

std::string roleName(Role r) {
  switch (r) {
    case Role::None:
      return "";
    case Role::InputRaster:
      return "input_raster";
    case Role::InputVector:
      return "input_vector";
    case Role::InputFile:
      return "input_file";
    case Role::OutputVector:
      return "output_vector";
    case Role::OutputRaster:
      return "output_raster";
    case Role::OutputFolder:
      return "output_folder";
    case Role::OutputFile:
      return "output_file";
    case Role::Crs:
      return "crs";
  }
  return "";
}

std::string typeName(ValueType t) {
  switch (t) {
    case ValueType::Flag:
      return "flag";
    case ValueType::Integer:
      return "integer";
    case ValueType::Real:
      return "real";
    case ValueType::String:
      return "string";
    case ValueType::Choice:
      return "choice";
  }
  return "";
}

void checkValue(const OptionSpec& spec, const std::string& value) {
  if (spec.type == ValueType::Integer || spec.type == ValueType::Real) {
    errno = 0;
    char* end = nullptr;
    const double v = spec.type == ValueType::Integer
                         ? static_cast<double>(std::strtoll(value.c_str(), &end, 10))
                         : std::strtod(value.c_str(), &end);
    const char* expected = spec.type == ValueType::Integer ? "an integer" : "a number";
    if (value.empty() || *end != '\0')
      throw UsageError(spec.name + " expects " + expected + ", got '" + value + "'");
    if (errno == ERANGE || !std::isfinite(v))
      throw UsageError(spec.name + " expects a finite " +
                       (spec.type == ValueType::Integer ? "integer" : "number") + ", got '" + value + "'");
    if (spec.minimum && v < *spec.minimum)
      throw UsageError(spec.name + " must be at least " + CPLSPrintf("%g", *spec.minimum) + ", got " + value);
    if (spec.maximum && v > *spec.maximum)
      throw UsageError(spec.name + " must be at most " + CPLSPrintf("%g", *spec.maximum) + ", got " + value);
  }
  if (spec.type == ValueType::Choice &&
      std::find(spec.choices.begin(), spec.choices.end(), value) == spec.choices.end()) {
    std::string list;
    for (const std::string& c : spec.choices) list += (list.empty() ? "" : ", ") + c;
    throw UsageError(spec.name + " must be one of " + list + ", got '" + value + "'");
  }
}

/// Prints GDAL's "0...10...20..." progress line, or "PROGRESS <pct> <stage>" lines.
class ProgressPrinter {
 public:
  enum class Style { Gdal, Lines, None };
  explicit ProgressPrinter(Style style) : style_(style) {}

  bool operator()(double fraction, std::string_view stage) {
    // Once an output is in place the run can no longer be undone: it finishes and says so.
    if (gInterrupted && !io::anyOutputCommitted()) return false;
    if (style_ == Style::Gdal) {
      const int target = static_cast<int>(fraction * 40.0 + 1e-9);
      while (printedSteps_ <= target && printedSteps_ <= 40) {
        if (printedSteps_ % 4 == 0)
          std::printf("%d", printedSteps_ / 4 * 10);
        else
          std::printf(".");
        ++printedSteps_;
      }
      if (fraction >= 1.0 && !done_) {
        std::printf(" - done.\n");
        done_ = true;
      }
      std::fflush(stdout);
    } else if (style_ == Style::Lines) {
      const double pct = std::floor(fraction * 1000.0) / 10.0;
      if (pct != lastPct_ || stage != lastStage_) {
        std::printf("PROGRESS %.1f %.*s\n", pct, static_cast<int>(stage.size()), stage.data());
        std::fflush(stdout);
        lastPct_ = pct;
        lastStage_ = std::string(stage);
      }
    }
    return true;
  }

 private:
  Style style_;
  int printedSteps_ = 0;
  bool done_ = false;
  double lastPct_ = -1.0;
  std::string lastStage_;
};

void printTopHelp(std::ostream& out) {
  out << "Usage: urbanvec <subcommand> [options] <inputs...> <output>\n"
         "       urbanvec --version | --help | --json-usage | <subcommand> --help\n\n"
         "urbanvec turns gridded urban land-use data into a vector city (roads, blocks, parcels)\n"
         "and provides the neighbouring tools of procedural urban modelling.\n\nSubcommands:\n";
  std::vector<const Registered*> sorted;
  for (const Registered& r : registry()) sorted.push_back(&r);
  std::sort(sorted.begin(), sorted.end(), [](auto* a, auto* b) { return a->spec.name < b->spec.name; });
  for (const Registered* r : sorted) {
    std::string name = r->spec.name;
    name.resize(std::max<size_t>(name.size(), 16), ' ');
    out << "  " << name << r->spec.summary << "\n";
  }
  out << "\nCommon options: -q, -progress gdal|lines|none, --config KEY VALUE, --help, --json-usage\n"
         "Exit status: 0 success, 1 failure, 2 usage error, 3 cancelled.\n";
}

/// Every path the run reads (input roles of positionals and options): outputs never replace them.
std::vector<std::string> inputPaths(const CommandSpec& spec, const ParsedArgs& parsed) {
  auto isInput = [](Role r) {
    return r == Role::InputRaster || r == Role::InputVector || r == Role::InputFile;
  };
  std::vector<std::string> paths;
  for (size_t i = 0; i < spec.positionals.size() && i < parsed.positionals().size(); ++i)
    if (isInput(spec.positionals[i].role)) paths.push_back(parsed.positionals()[i]);
  for (const OptionSpec& o : spec.options)
    if (isInput(o.role) && parsed.given(o.name))
      for (const std::string& v : parsed.values(o.name)) paths.push_back(v);
  return paths;
}

}  // namespace

std::string numberText(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.10g", value);
  return buffer;
}

bool ParsedArgs::has(const std::string& name) const {
  auto it = values_.find(name);
  return it != values_.end() && !it->second.empty();
}
bool ParsedArgs::given(const std::string& name) const {
  auto it = given_.find(name);
  return it != given_.end() && it->second;
}
std::string ParsedArgs::str(const std::string& name) const {
  auto it = values_.find(name);
  if (it == values_.end() || it->second.empty()) throw internalError("option " + name + " has no value");
  return it->second.front();
}
double ParsedArgs::real(const std::string& name) const {
  return std::strtod(str(name).c_str(), nullptr);
}
long long ParsedArgs::integer(const std::string& name) const {
  return std::strtoll(str(name).c_str(), nullptr, 10);
}
std::vector<std::string> ParsedArgs::values(const std::string& name) const {
  auto it = values_.find(name);
  return it == values_.end() ? std::vector<std::string>{} : it->second;
}

bool registerCommand(CommandSpec spec, CommandFunction run) {
  registry().push_back({std::move(spec), std::move(run)});
  return true;
}

std::vector<OptionSpec> vectorOutputOptions() {
  std::vector<OptionSpec> o;
  o.push_back(
      option("-of", ValueType::String, "<format>",
             "Output vector format (OGR driver name); default from the output extension, GPKG otherwise.")
          .isAdvanced());
  o.push_back(option("-lco", ValueType::String, "<NAME=VALUE>", "Layer creation option (repeatable).")
                  .many()
                  .isAdvanced());
  o.push_back(option("-dsco", ValueType::String, "<NAME=VALUE>", "Dataset creation option (repeatable).")
                  .many()
                  .isAdvanced());
  o.push_back(option("-overwrite", ValueType::Flag, "", "Replace the output if it exists."));
  return o;
}

std::vector<OptionSpec> rasterOutputOptions() {
  std::vector<OptionSpec> o;
  o.push_back(option("-co", ValueType::String, "<NAME=VALUE>", "Raster creation option (repeatable).")
                  .many()
                  .isAdvanced());
  o.push_back(option("-overwrite", ValueType::Flag, "", "Replace the output if it exists."));
  return o;
}

OptionSpec seedOption() {
  return option("-seed", ValueType::Integer, "<N>",
                "Seed of the random generator: the same seed gives the same output.")
      .byDefault("1")
      .atLeast(0);
}

ParsedArgs parseArguments(const CommandSpec& spec, const std::vector<std::string>& args) {
  ParsedArgs parsed;
  std::vector<OptionSpec> all = spec.options;
  for (const OptionSpec& c : commonOptions()) all.push_back(c);
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    if (!looksLikeOption(arg)) {
      parsed.positionals_.push_back(arg);
      continue;
    }
    const std::string name = normalise(arg);
    const OptionSpec* opt = findOption(all, name);
    if (!opt) throw UsageError("unknown option '" + arg + "' (see 'urbanvec " + spec.name + " --help')");
    if (parsed.given(opt->name) && !opt->repeatable)
      throw UsageError("option " + opt->name + " is given twice");
    parsed.given_[opt->name] = true;
    auto& values = parsed.values_[opt->name];
    if (opt->type == ValueType::Flag) {
      values.push_back("true");
      continue;
    }
    for (int k = 0; k < opt->arity; ++k) {
      if (i + 1 >= args.size())
        throw UsageError("option " + opt->name + " needs " + std::to_string(opt->arity) + " value" +
                         (opt->arity > 1 ? "s " : " ") + opt->metavar);
      const std::string& v = args[++i];
      checkValue(*opt, v);
      values.push_back(v);
    }
  }
  for (const OptionSpec& opt : all)
    if (!parsed.given(opt.name) && !opt.defaultValue.empty()) parsed.values_[opt.name] = {opt.defaultValue};
  size_t required = 0;
  for (const PositionalSpec& p : spec.positionals) required += p.optional ? 0 : 1;
  if (parsed.positionals_.size() < required || parsed.positionals_.size() > spec.positionals.size()) {
    std::string names;
    for (const PositionalSpec& p : spec.positionals) names += " <" + p.name + ">";
    throw UsageError("'urbanvec " + spec.name + "' expects" + names + ", got " +
                     std::to_string(parsed.positionals_.size()) + " argument" +
                     (parsed.positionals_.size() == 1 ? "" : "s"));
  }
  return parsed;
}

std::string helpText(const CommandSpec& spec) {
  std::ostringstream out;
  out << "Usage: urbanvec " << spec.name << " [options]";
  for (const PositionalSpec& p : spec.positionals)
    out << (p.optional ? " [<" : " <") << p.name << (p.optional ? ">]" : ">");
  out << "\n\n" << spec.summary << "\n";
  if (!spec.description.empty()) out << "\n" << spec.description << "\n";
  out << "\nArguments:\n";
  for (const PositionalSpec& p : spec.positionals) out << "  <" << p.name << ">\n      " << p.help << "\n";
  out << "\nOptions:\n";
  auto print = [&](const OptionSpec& o) {
    out << "  " << o.name << (o.metavar.empty() ? "" : " " + o.metavar) << "\n      " << o.help;
    if (!o.choices.empty()) {
      out << " Values:";
      for (size_t i = 0; i < o.choices.size(); ++i) out << (i ? ", " : " ") << o.choices[i];
      out << ".";
    }
    if (!o.unit.empty()) out << " Unit: " << o.unit << ".";
    if (!o.defaultValue.empty()) out << " Default: " << o.defaultValue << ".";
    out << "\n";
  };
  for (const OptionSpec& o : spec.options) print(o);
  for (const OptionSpec& o : commonOptions()) print(o);
  out << "  --help\n      Prints this help.\n  --json-usage\n      Prints this command's options as JSON.\n";
  if (!spec.examples.empty()) {
    out << "\nExamples:\n";
    for (const std::string& e : spec.examples) out << "  " << e << "\n";
  }
  return out.str();
}

std::string jsonUsage(const CommandSpec& spec) {
  nlohmann::ordered_json j;
  j["name"] = spec.name;
  j["summary"] = spec.summary;
  j["description"] = spec.description;
  j["group"] = spec.group;
  j["version"] = kVersion;
  j["positionals"] = nlohmann::json::array();
  for (const PositionalSpec& p : spec.positionals)
    j["positionals"].push_back(
        {{"name", p.name}, {"help", p.help}, {"role", roleName(p.role)}, {"optional", p.optional}});
  j["options"] = nlohmann::json::array();
  for (const OptionSpec& o : spec.options) {
    nlohmann::ordered_json oj;
    oj["name"] = o.name;
    oj["type"] = typeName(o.type);
    oj["arity"] = o.type == ValueType::Flag ? 0 : o.arity;
    oj["metavar"] = o.metavar;
    oj["help"] = o.help;
    oj["default"] =
        o.defaultValue.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json(o.defaultValue);
    oj["choices"] = o.choices;
    oj["repeatable"] = o.repeatable;
    oj["unit"] = o.unit;
    oj["role"] = roleName(o.role);
    oj["minimum"] = o.minimum ? nlohmann::ordered_json(*o.minimum) : nlohmann::ordered_json();
    oj["maximum"] = o.maximum ? nlohmann::ordered_json(*o.maximum) : nlohmann::ordered_json();
    oj["advanced"] = o.advanced;
    j["options"].push_back(oj);
  }
  j["output_layers"] = spec.outputLayers;
  return j.dump(2) + "\n";
}

int runMain(int argc, char** argv) {
  std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h" || args[0] == "-help") {
    printTopHelp(std::cout);
    return args.empty() ? 2 : 0;
  }
  if (args[0] == "--json-usage") {
    // Every subcommand's usage in one document: the QGIS provider builds its algorithms from it.
    std::vector<const Registered*> sorted;
    for (const Registered& r : registry()) sorted.push_back(&r);
    std::sort(sorted.begin(), sorted.end(), [](auto* a, auto* b) { return a->spec.name < b->spec.name; });
    nlohmann::ordered_json all;
    all["program"] = "urbanvec";
    all["version"] = kVersion;
    all["commands"] = nlohmann::json::array();
    for (const Registered* r : sorted)
      all["commands"].push_back(nlohmann::ordered_json::parse(jsonUsage(r->spec)));
    std::cout << all.dump(2) << "\n";
    return 0;
  }
  if (args[0] == "--version" || args[0] == "-version") {
    std::cout << "urbanvec " << kVersion << "\n";
    return 0;
  }
  const Registered* command = findCommand(args[0]);
  if (!command) {
    std::cerr << "ERROR: unknown subcommand '" << args[0] << "' (see 'urbanvec --help')\n";
    return 2;
  }
  std::vector<std::string> rest(args.begin() + 1, args.end());
  for (const std::string& a : rest) {
    if (a == "--help" || a == "-help" || a == "-h") {
      std::cout << helpText(command->spec);
      return 0;
    }
    if (a == "--json-usage") {
      std::cout << jsonUsage(command->spec);
      return 0;
    }
  }
  try {
    ParsedArgs parsed = parseArguments(command->spec, rest);
    const std::vector<std::string> config = parsed.values("--config");
    for (size_t i = 0; i + 1 < config.size(); i += 2)
      CPLSetConfigOption(config[i].c_str(), config[i + 1].c_str());
    io::ensureGdal();
    const bool quiet = parsed.flag("-q");
    const std::string style = parsed.str("-progress");
    auto printer = std::make_shared<ProgressPrinter>(quiet || style == "none" ? ProgressPrinter::Style::None
                                                     : style == "lines"       ? ProgressPrinter::Style::Lines
                                                                              : ProgressPrinter::Style::Gdal);
    std::signal(SIGINT, onSignal);
    std::signal(SIGTERM, onSignal);
    CommandContext context;
    context.inputs = inputPaths(command->spec, parsed);
    context.quiet = quiet;
    context.out = &std::cout;
    context.progress =
        monotonicProgress([printer](double f, std::string_view s) { return (*printer)(f, s); });
    context.warn = [](const std::string& message) {
      std::fflush(stdout);
      std::cerr << "Warning: " << message << "\n";
    };
    command->run(parsed, context);
    reportProgress(context.progress, 1.0, "done");
    if (gInterrupted)
      context.warn(
          "interrupted while the output was being moved into place; the run finished, and its output is "
          "complete");
    return 0;
  } catch (const UsageError& e) {
    std::cerr << "ERROR: " << e.what() << "\n";
    return 2;
  } catch (const Cancelled&) {
    std::fflush(stdout);
    std::cerr << "ERROR: cancelled; no output was written\n";
    return 3;
  } catch (const Error& e) {
    std::fflush(stdout);
    std::cerr << "ERROR: " << e.what() << "\n";
    // An option value the command cannot use is a usage error, whether the parser or the command
    // found it (README: exit status 2).
    return e.kind() == ErrorKind::InvalidOption ? 2 : 1;
  } catch (const std::bad_alloc&) {
    std::fflush(stdout);
    std::cerr << "ERROR: out of memory\n";
    return 1;
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::cerr << "ERROR: internal error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace urbanvec::app
