// The command framework behind `urbanvec <subcommand>`: each subcommand declares its options once
// (CommandSpec); parsing, `--help`, `--json-usage` (read by the QGIS provider), progress printing,
// error reporting and exit codes all derive from that declaration (CONVENTIONS.md "The command").
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "urbanvec/core/progress.hpp"

namespace urbanvec::app {

enum class ValueType { Flag, Integer, Real, String, Choice };

/// What an argument is, so the QGIS provider can pick a parameter type.
enum class Role {
  None,
  InputRaster,
  InputVector,
  InputFile,
  OutputVector,
  OutputRaster,
  OutputFolder,
  OutputFile,
  Crs,
};

struct OptionSpec {
  std::string name;  ///< "-tr" (GDAL style: one dash)
  ValueType type = ValueType::Flag;
  int arity = 1;                     ///< values taken (e.g. -te takes 4); 0 for flags
  std::string metavar;               ///< "<metres>"
  std::string help;                  ///< one sentence
  std::string defaultValue;          ///< as text; empty = no default
  std::vector<std::string> choices;  ///< for ValueType::Choice
  bool repeatable = false;           ///< may be given several times (e.g. -lco)
  std::string unit;                  ///< "m", "cells", "degrees"...
  Role role = Role::None;
  std::optional<double> minimum;  ///< inclusive bounds checked by the parser
  std::optional<double> maximum;
  bool advanced = false;  ///< shown in QGIS's "Advanced parameters"

  // Chainable setters: option("-tr", ValueType::Real, "<metres>", "...").byDefault("12").unit("m")
  OptionSpec& byDefault(std::string v) {
    defaultValue = std::move(v);
    return *this;
  }
  OptionSpec& withUnit(std::string u) {
    unit = std::move(u);
    return *this;
  }
  OptionSpec& withRole(Role r) {
    role = r;
    return *this;
  }
  OptionSpec& atLeast(double v) {
    minimum = v;
    return *this;
  }
  OptionSpec& atMost(double v) {
    maximum = v;
    return *this;
  }
  OptionSpec& values(int n) {
    arity = n;
    return *this;
  }
  OptionSpec& oneOf(std::vector<std::string> c) {
    choices = std::move(c);
    type = ValueType::Choice;
    return *this;
  }
  OptionSpec& many() {
    repeatable = true;
    return *this;
  }
  OptionSpec& isAdvanced() {
    advanced = true;
    return *this;
  }
};

/// A number as option-default text: up to 10 significant digits, no trailing zeros ("0.3", "1e-06").
std::string numberText(double value);

/// Starts an option declaration; flags take no value, every other type one value unless values(n).
inline OptionSpec option(std::string name, ValueType type, std::string metavar, std::string help) {
  OptionSpec o;
  o.name = std::move(name);
  o.type = type;
  o.arity = type == ValueType::Flag ? 0 : 1;
  o.metavar = std::move(metavar);
  o.help = std::move(help);
  return o;
}

struct PositionalSpec {
  std::string name;  ///< "input", "output_dir"
  std::string help;
  Role role = Role::None;
  bool optional = false;
};

struct CommandSpec {
  std::string name;
  std::string summary;      ///< one line for `urbanvec --help`
  std::string description;  ///< paragraph(s) for `urbanvec <name> --help`
  std::string group;        ///< QGIS toolbox group
  std::vector<PositionalSpec> positionals;
  std::vector<OptionSpec> options;
  std::vector<std::string> examples;
  /// Layers written to the vector output (for the QGIS provider's outputs); may be empty.
  std::vector<std::string> outputLayers;
};

/// Parsed arguments, with defaults filled in.
class ParsedArgs {
 public:
  bool has(const std::string& name) const;    ///< given on the command line or has a default
  bool given(const std::string& name) const;  ///< given on the command line
  bool flag(const std::string& name) const { return given(name); }
  std::string str(const std::string& name) const;  ///< first value
  double real(const std::string& name) const;
  long long integer(const std::string& name) const;
  std::vector<std::string> values(const std::string& name) const;  ///< all values, every occurrence
  const std::vector<std::string>& positionals() const { return positionals_; }

  std::map<std::string, std::vector<std::string>> values_;
  std::map<std::string, bool> given_;
  std::vector<std::string> positionals_;
};

/// What a running subcommand may use besides its arguments.
struct CommandContext {
  Progress progress;  ///< prints progress as asked (-q, -progress); checks for cancellation
  std::function<void(const std::string&)> warn;  ///< prints "Warning: ..." on stderr
  std::ostream* out = nullptr;                   ///< stdout (reports, tables)
  bool quiet = false;
  /// Paths the run reads (from the input roles of the spec): pass them to io::OutputRules::inputs.
  std::vector<std::string> inputs;
};

using CommandFunction = std::function<void(const ParsedArgs&, CommandContext&)>;

/// Registers a subcommand; called from static initialisers in src/cli.
bool registerCommand(CommandSpec spec, CommandFunction run);

/// The options most output-writing commands share: -of, -lco, -co, -overwrite.
std::vector<OptionSpec> vectorOutputOptions();
std::vector<OptionSpec> rasterOutputOptions();
OptionSpec seedOption();

/// Parses argv, runs the subcommand, prints errors; returns the exit code
/// (0 success, 1 failure, 2 usage error, 3 cancelled).
int runMain(int argc, char** argv);

/// A usage error (unknown option, missing value, wrong count of inputs): exit status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parses arguments against a spec (exposed for tests); throws UsageError.
ParsedArgs parseArguments(const CommandSpec& spec, const std::vector<std::string>& args);
/// `urbanvec <sub> --help` text and the `--json-usage` document.
std::string helpText(const CommandSpec& spec);
std::string jsonUsage(const CommandSpec& spec);

}  // namespace urbanvec::app
