// rktsph — command line: run, check, validate.
// Exit status: 0 success, 1 validation failed, 2 bad input (case file or arguments),
// 3 a run diverged or could not proceed.
#include <fmt/format.h>
#include <omp.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <filesystem>
#include <iostream>

#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/driver/run_case.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/validation/validation_case.hpp"

namespace {

using namespace rktsph;

constexpr int kExitValidationFailed = 1;
constexpr int kExitInput = 2;
constexpr int kExitRun = 3;

std::vector<CaseOverride> parse_overrides(const std::vector<std::string>& texts) {
  std::vector<CaseOverride> overrides;
  for (const std::string& text : texts)
    overrides.push_back(parse_override(text));
  return overrides;
}

std::filesystem::path default_cases_directory() {
  if (const char* env = std::getenv("RKTSPH_CASES")) return env;
  if (std::filesystem::exists("cases")) return "cases";
  return std::filesystem::path(RKTSPH_SOURCE_DIR) / "cases";
}

int command_run(const std::string& case_path, const std::string& output, int threads,
                const std::vector<std::string>& sets, bool quiet) {
  if (threads > 0) omp_set_num_threads(threads);
  const CaseDescription description = read_case_file(case_path, parse_overrides(sets));
  const std::filesystem::path directory = output.empty()
                                              ? std::filesystem::path("results") / description.name
                                              : std::filesystem::path(output);
  RunOptions options;
  options.quiet = quiet;
  options.progress_stream = &std::cerr;
  options.progress_is_terminal = isatty(STDERR_FILENO) != 0;
  const RunOutcome outcome = run_case(description, directory, options);
  if (outcome.status != RunStatus::Completed) {
    std::cerr << "rktsph: " << outcome.message << "\n"
              << "rktsph: the last good output is kept in " << directory.string() << "\n";
    return kExitRun;
  }
  if (!quiet)
    std::cout << fmt::format(
        "Finished {} steps in {:.2f} s. Results: {}/ (series.pvd for ParaView, probes.csv, "
        "summary.json)\n",
        outcome.steps, outcome.wall_seconds, directory.string());
  return 0;
}

int command_check(const std::string& case_path, const std::vector<std::string>& sets) {
  const CaseDescription description = read_case_file(case_path, parse_overrides(sets));
  // Building the simulation checks materials, groups, boundary conditions and stencils too.
  const Simulation simulation(description);
  std::cout << fmt::format("{}: OK ({} SPH nodes, {} stress points, dt = {:.4g} s, {} steps)\n",
                           case_path, simulation.nodes().sph_nodes.size(),
                           simulation.nodes().stress_points.size(), simulation.time_step(),
                           simulation.total_steps());
  return 0;
}

int command_validate(std::vector<std::string> names, bool all, bool quick, bool json,
                     const std::string& output, int threads) {
  if (threads > 0) omp_set_num_threads(threads);
  const auto& cases = validation_cases();
  if (all || names.empty())
    for (const ValidationCase& c : cases)
      names.push_back(c.name);
  std::vector<const ValidationCase*> selected;
  for (const std::string& name : names) {
    const auto it = std::find_if(cases.begin(), cases.end(),
                                 [&](const ValidationCase& c) { return c.name == name; });
    if (it == cases.end()) {
      std::string known;
      for (const ValidationCase& c : cases)
        known += (known.empty() ? "" : ", ") + c.name;
      throw InputError({}, "validate", name, "unknown validation case",
                       known.empty() ? "(none bundled yet)" : known);
    }
    if (std::find(selected.begin(), selected.end(), &*it) == selected.end())
      selected.push_back(&*it);
  }
  ValidationContext context;
  context.cases_directory = default_cases_directory();
  context.output_directory = output.empty() ? "results/validation" : output;
  context.quick = quick;
  bool all_passed = true;
  for (const ValidationCase* validation : selected) {
    const ValidationResult result = run_validation(*validation, context);
    all_passed = all_passed && result.passed;
    if (json) {
      std::cout << validation_json_line(result) << std::endl;
      continue;
    }
    std::cout << fmt::format("{:<28} {}  ({:.1f} s)\n", result.case_name,
                             result.passed ? "PASSED" : "FAILED", result.wall_seconds);
    if (!result.error.empty()) std::cout << "    error: " << result.error << "\n";
    for (const CheckResult& check : result.checks)
      std::cout << fmt::format("    {:<32} {:>12.5g} (reference {:.5g}, tolerance {:.3g} {})  {}\n",
                               check.name, check.value, check.reference, check.tolerance,
                               check.unit, check.passed ? "ok" : "FAIL");
  }
  return all_passed ? 0 : kExitValidationFailed;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rktsph: Runge-Kutta Taylor SPH for the dynamics of dry and saturated soils"};
  app.set_version_flag("--version", std::string("rktsph ") + RKTSPH_VERSION);
  app.require_subcommand(1);

  std::string case_path, output;
  int threads = 0;
  std::vector<std::string> sets;
  bool quiet = false;

  CLI::App* run = app.add_subcommand("run", "Run a case file and write its results");
  run->add_option("case", case_path, "Case file (YAML)")->required();
  run->add_option("-o,--output", output, "Output folder (default results/<case name>)");
  run->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  run->add_option("--set", sets, "Override a case key: --set time.end=0.1 (repeatable)");
  run->add_flag("-q,--quiet", quiet, "No progress display");

  CLI::App* check = app.add_subcommand("check", "Validate a case file without running it");
  check->add_option("case", case_path, "Case file (YAML)")->required();
  check->add_option("--set", sets, "Override a case key (repeatable)");

  std::vector<std::string> names;
  bool all = false, quick = false, json = false;
  CLI::App* validate =
      app.add_subcommand("validate", "Run bundled validation cases against their references");
  validate->add_option("names", names, "Validation cases to run (default: all)");
  validate->add_flag("--all", all, "Run every bundled case");
  validate->add_flag("--quick", quick, "Coarser, shorter variants (as run by make test)");
  validate->add_flag("--json", json, "One JSON object per case per line");
  validate->add_option("-o,--output", output, "Folder for the runs (default results/validation)");
  validate->add_option("--threads", threads, "OpenMP threads")->check(CLI::Range(1, 1024));

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : kExitInput;
  }

  try {
    if (*run) return command_run(case_path, output, threads, sets, quiet);
    if (*check) return command_check(case_path, sets);
    if (*validate) return command_validate(names, all, quick, json, output, threads);
  } catch (const InputError& error) {
    std::cerr << "rktsph: " << error.what() << "\n";
    return kExitInput;
  } catch (const RunError& error) {
    std::cerr << "rktsph: " << error.what() << "\n";
    return kExitRun;
  } catch (const std::exception& error) {
    std::cerr << "rktsph: internal error: " << error.what() << "\n";
    return kExitRun;
  }
  return 0;
}
