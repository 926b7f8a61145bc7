// rktsph — command line: run, check, validate, plot, fos.
// Exit status: 0 success, 1 validation failed, 2 bad input (case file, arguments, an output
// folder that cannot be created or holds results without --overwrite), 3 a run diverged, failed
// or could not proceed (also: output folder in use by another run), 130/143 interrupted by
// SIGINT/SIGTERM.
#include <fcntl.h>
#include <fmt/format.h>
#include <omp.h>
#include <sys/wait.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "check_line.hpp"
#include "rktsph/case/case_reader.hpp"
#include "rktsph/core/build_info.hpp"
#include "rktsph/core/error.hpp"
#include "rktsph/driver/interrupt.hpp"
#include "rktsph/driver/run_case.hpp"
#include "rktsph/output/gmsh_writer.hpp"
#include "rktsph/output/run_observers.hpp"
#include "rktsph/simulation/case_warnings.hpp"
#include "rktsph/simulation/simulation.hpp"
#include "rktsph/strength_reduction/strength_reduction.hpp"
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

// The folder of the validation cases, and how it was chosen (for the error when a case is not
// there). The bundled cases unless told otherwise: a user's own ./cases folder is theirs, not the
// validation's.
struct CasesFolder {
  std::filesystem::path path;
  std::string chosen_by;
};

CasesFolder validation_cases_folder(const std::string& option) {
  if (!option.empty()) return {option, "--cases"};
  if (const char* env = std::getenv("RKTSPH_CASES")) return {env, "RKTSPH_CASES"};
  return {std::filesystem::path(RKTSPH_SOURCE_DIR) / "cases",
          "the bundled cases; --cases DIR or RKTSPH_CASES=DIR for others"};
}

// The report and plotting tools are Python scripts (matplotlib) in tools/; found like the cases.
std::filesystem::path tools_directory() {
  if (const char* env = std::getenv("RKTSPH_TOOLS")) return env;
  if (std::filesystem::exists("tools/make_report.py")) return "tools";
  return std::filesystem::path(RKTSPH_SOURCE_DIR) / "tools";
}

/// Runs a program with its arguments (no shell, so no quoting problems; a name without a slash
/// is looked up in PATH) and returns its exit status, or -1 if it could not be started or did not
/// exit normally. `silent`: its output goes to /dev/null.
int run_program(const std::vector<std::string>& arguments, bool silent = false) {
  std::vector<char*> argv;
  for (const std::string& argument : arguments)
    argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  std::cout.flush();
  const pid_t child = fork();
  if (child < 0) return -1;
  if (child == 0) {
    if (silent) {
      const int null = open("/dev/null", O_WRONLY);
      dup2(null, STDOUT_FILENO);
      dup2(null, STDERR_FILENO);
    }
    execvp(argv[0], argv.data());
    std::cerr << "rktsph: cannot start " << arguments[0] << ": " << std::strerror(errno) << "\n";
    _exit(127);
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// The interpreter of the tools: the python3 of PATH, as a shell would take it (a virtual
// environment's, with its own matplotlib), unless that one lacks matplotlib and Debian's
// /usr/bin/python3, where `make deps-report` installs it, has it.
std::string tools_python() {
  for (const char* candidate : {"python3", "/usr/bin/python3"})
    if (run_program({candidate, "-c", "import matplotlib"}, true) == 0) return candidate;
  return "python3";  // the tool then says that matplotlib is missing
}

/// Runs a tools/ script; its own messages go to stderr. Throws RunError if it cannot start.
int run_tool(const std::string& script, std::vector<std::string> arguments) {
  const std::filesystem::path path = tools_directory() / script;
  if (!std::filesystem::exists(path))
    throw RunError(
        fmt::format("{} not found (set RKTSPH_TOOLS to the tools/ folder)", path.string()));
  const std::string python = tools_python();
  arguments.insert(arguments.begin(), {python, path.string()});
  const int status = run_program(arguments);
  if (status == 127 || status < 0)
    throw RunError(fmt::format("could not run {} {} (is python3 installed and on PATH?)", python,
                               path.string()));
  return status;
}

// A count option: "abc" is "not an integer", 0 or 5000 "not in 1..1024" (CLI11's range check
// alone calls every non-number "not in range").
CLI::Validator integer_in_range(int low, int high) {
  return CLI::Validator(
      [low, high](std::string& text) -> std::string {
        int value = 0;
        const char* end = text.data() + text.size();
        const auto [stop, error] = std::from_chars(text.data(), end, value);
        const bool digits_only =
            stop == end && (error == std::errc() || error == std::errc::result_out_of_range);
        if (!digits_only)
          return fmt::format("'{}' is not an integer (expected a whole number in {}..{})", text,
                             low, high);
        if (error != std::errc() || value < low || value > high)
          return fmt::format("'{}' is not in {}..{}", text, low, high);
        return {};
      },
      fmt::format("INT in [{} - {}]", low, high));
}

std::string command_names(const CLI::App& app) {
  std::string known;
  for (const CLI::App* command : app.get_subcommands({}))
    known += (known.empty() ? "" : ", ") + command->get_name();
  return known;
}

// `rktsph` alone: CLI11 would only say "A subcommand is required"; a first-time user needs the
// commands and what each does.
bool explain_missing_command(const CLI::App& app, int argc) {
  if (argc >= 2) return false;
  std::string text = "rktsph: a command is needed (rktsph COMMAND --help for its options):\n";
  for (const CLI::App* command : app.get_subcommands({}))
    text += fmt::format("  {:<10} {}\n", command->get_name(), command->get_description());
  std::cerr << text;
  return true;
}

// `rktsph foo`: CLI11 would only say "A subcommand is required".
bool reject_unknown_command(const CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return false;
  for (const CLI::App* command : app.get_subcommands({}))
    if (command->get_name() == argv[1]) return false;
  const std::string known = command_names(app);
  std::cerr << fmt::format("rktsph: unknown command '{}'; the commands are {} (rktsph --help)\n",
                           argv[1], known);
  return true;
}

// 128 + the signal, as a shell reports a program ended by it: 130 for SIGINT, 143 for SIGTERM.
int interrupted_exit_status() {
  return 128 + InterruptHandler::received_signal();
}

// The folder a run writes into: the restarted run's own, or -o, or results/<case name>.
std::filesystem::path run_directory_for(const CaseDescription& description,
                                        const std::string& output, const std::string& restart) {
  if (!restart.empty()) {
    const bool same = output.empty() || std::filesystem::weakly_canonical(output) ==
                                            std::filesystem::weakly_canonical(restart);
    if (!same)
      throw InputError({}, "-o", output, "a restarted run continues in its own folder",
                       fmt::format("no -o with --restart, or -o {}", restart));
    return restart;
  }
  return output.empty() ? std::filesystem::path("results") / description.name
                        : std::filesystem::path(output);
}

int command_run(const std::string& case_path, const std::string& output, int threads,
                const std::vector<std::string>& sets, bool quiet, bool overwrite,
                const std::string& restart, const SimulationLimits& limits) {
  if (threads > 0) omp_set_num_threads(threads);
  const CaseDescription description = read_case_file(case_path, parse_overrides(sets));
  if (overwrite && !restart.empty())
    throw InputError({}, "--overwrite", "--restart " + restart,
                     "a restarted run continues its own results",
                     "either --overwrite or --restart");
  const std::filesystem::path directory = run_directory_for(description, output, restart);
  RunOptions options;
  options.restart = !restart.empty();
  options.quiet = quiet;
  options.progress_stream = &std::cerr;
  options.progress_is_terminal = isatty(STDERR_FILENO) != 0;
  options.existing_results = overwrite ? ExistingResults::Overwrite : ExistingResults::Refuse;
  const InterruptHandler interrupts;
  options.stop_check = &InterruptHandler::stop_reason;
  options.limits = limits;
  const RunOutcome outcome = run_case(description, directory, options);
  if (outcome.status == RunStatus::Interrupted) {
    std::cerr << "rktsph: " << outcome.message << "\n"
              << "rktsph: the results up to that step are in " << directory.string() << "\n";
    return interrupted_exit_status();
  }
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

int command_check(const std::string& case_path, const std::vector<std::string>& sets, int threads,
                  const SimulationLimits& limits, const std::string& mesh_path) {
  // The stencils are built here as in a run, so the threads a run would use are honoured.
  if (threads > 0) omp_set_num_threads(threads);
  const CaseDescription description = read_case_file(case_path, parse_overrides(sets));
  if (!mesh_path.empty() && description.dimension != 2)
    throw InputError(
        {}, "--write-mesh", mesh_path,
        fmt::format("a {}D case has no cells a mesh file can hold", description.dimension),
        "a 2D case");
  // Building the simulation checks materials, groups, boundary conditions and stencils too; the
  // observers' settings are checked as run checks them, without writing anything.
  const Simulation simulation(description, limits);
  check_run_observers(simulation);
  const std::vector<CaseWarning> warnings = case_warnings(simulation);
  for (const CaseWarning& warning : warnings)
    std::cerr << "rktsph: " << warning.to_string() << "\n";
  std::cerr.flush();
  const std::string warning_count =
      warnings.empty()
          ? ""
          : fmt::format(", {} warning{}", warnings.size(), warnings.size() > 1 ? "s" : "");
  std::cout << fmt::format(
      "{}: OK ({} SPH nodes, {} stress points, dt = {:.4g} s, {} steps, memory about {:.3g} "
      "MB{})\n",
      case_path, simulation.nodes().sph_nodes.size(), simulation.cells().stress_points.size(),
      simulation.time_step(), simulation.total_steps(), simulation.estimated_memory() * 1e-6,
      warning_count);
  if (!mesh_path.empty()) {
    const NodeSets& nodes = simulation.nodes();
    write_gmsh_mesh(mesh_path, nodes);
    std::cout << fmt::format("mesh written to {} ({} nodes, {} cells, Gmsh MSH 2.2)\n", mesh_path,
                             nodes.sph_nodes.size(), nodes.cells.cell_count());
  }
  return 0;
}

int command_validate(std::vector<std::string> names, bool all, bool quick, bool json,
                     const std::string& output, const std::string& report, int threads, int jobs,
                     const std::vector<std::string>& sets, const std::string& cases_option) {
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
  // report.json goes next to the runs (<output>/<case>/), and the page refers to both, so the
  // runs of a report are kept in its folder.
  if (!report.empty() && !output.empty() &&
      std::filesystem::weakly_canonical(report) != std::filesystem::weakly_canonical(output))
    throw InputError({}, "validate --output", output, "the runs of a report go to its folder",
                     "the --report folder, or no --output");
  const CasesFolder cases_folder = validation_cases_folder(cases_option);
  if (!std::filesystem::is_directory(cases_folder.path))
    throw InputError({}, "validate --cases", cases_folder.path.string(),
                     fmt::format("no folder of validation cases here ({})", cases_folder.chosen_by),
                     "a folder holding <case>/case.yaml, such as the cases/ of the sources");
  ValidationContext context;
  context.cases_directory = cases_folder.path;
  context.output_directory = !report.empty()  ? report
                             : output.empty() ? "results/validation"
                                              : output;
  context.quick = quick;
  context.overrides = parse_overrides(sets);
  context.write_report = !report.empty();
  // Several cases run side by side, one per core, each on its share of the cores: the bundled
  // runs are small enough that a second OpenMP thread mostly waits at barriers.
  const int cores = std::max(omp_get_num_procs(), 1);
  if (jobs <= 0) jobs = selected.size() > 1 ? cores : 1;
  if (threads <= 0) threads = std::max(cores / jobs, 1);
  bool all_passed = true;
  run_validations(selected, context, jobs, threads, [&](const ValidationResult& result) {
    all_passed = all_passed && result.passed;
    if (json) {
      std::cout << validation_json_line(result) << std::endl;
      return;
    }
    std::cout << fmt::format("{:<28} {}  ({:.1f} s)\n", result.case_name,
                             result.passed ? "PASSED" : "FAILED", result.wall_seconds);
    if (!result.error.empty()) std::cout << "    error: " << result.error << "\n";
    if (result.error.find("cannot open the case file") != std::string::npos)
      std::cout << fmt::format("    (the cases were looked for in {}: {})\n",
                               cases_folder.path.string(), cases_folder.chosen_by);
    for (const CheckResult& check : result.checks)
      std::cout << check_line(check);
    std::cout << std::flush;
  });
  if (!report.empty()) {
    std::vector<std::string> arguments = {report};
    for (const ValidationCase* validation : selected)
      arguments.push_back(validation->name);
    if (run_tool("make_report.py", arguments) != 0) {
      std::cerr << "rktsph: the report in " << report << " is incomplete (see above)\n";
      return kExitRun;
    }
  }
  return all_passed ? 0 : kExitValidationFailed;
}

int command_plot(const std::string& run_directory, const std::string& field, int component,
                 double time, double magnification, const std::string& output) {
  std::vector<std::string> arguments = {run_directory,
                                        "--field",
                                        field,
                                        "--component",
                                        std::to_string(component),
                                        "--magnify",
                                        fmt::format("{:.17g}", magnification),
                                        "-o",
                                        output};
  if (time >= 0.0) arguments.insert(arguments.end(), {"--time", fmt::format("{:.17g}", time)});
  const int status = run_tool("plot_field.py", arguments);
  // plot_field.py: 2 for input it cannot use (no such run, field or component).
  if (status == 0) {
    std::cout << fmt::format("{}: particles drawn at X + {:g} u (X reference, u displacement)\n",
                             output, magnification);
    return 0;
  }
  return status == 2 ? kExitInput : kExitRun;
}

struct FosArguments {
  std::string case_path, output;
  std::vector<std::string> sets;
  std::vector<double> bracket = {1.0, 2.0};
  double tolerance = 0.01;
  FailureCriterion criterion;
  bool overwrite = false, quiet = false;
};

// `rktsph fos`: the factor of safety by strength reduction (docs/theory.md §10). Exit status 0
// with a factor, 1 when the bracket does not hold (no factor), 2 for bad input, 3 for a run that
// could not be set up, 130/143 interrupted.
int command_fos(const FosArguments& arguments) {
  const CaseDescription description =
      read_case_file(arguments.case_path, parse_overrides(arguments.sets));
  check_strength_reduction_case(description);
  const std::filesystem::path directory =
      arguments.output.empty() ? std::filesystem::path("results") / (description.name + "-fos")
                               : std::filesystem::path(arguments.output);
  const std::filesystem::path summary = directory / "fos.json";
  if (std::filesystem::exists(summary) && !arguments.overwrite)
    throw InputError({}, "--output", directory.string(),
                     "holds the results of an earlier strength reduction (fos.json)",
                     "--overwrite, or another folder with -o");
  StrengthReductionOptions options;
  options.stable = arguments.bracket.at(0);
  options.failing = arguments.bracket.at(1);
  options.tolerance = arguments.tolerance;
  options.criterion = arguments.criterion;
  options.existing_results =
      arguments.overwrite ? ExistingResults::Overwrite : ExistingResults::Refuse;
  const InterruptHandler interrupts;
  options.stop_check = &InterruptHandler::stop_reason;
  options.on_run = [&](const ReductionRun& run) {
    if (arguments.quiet) return;
    if (run.factor == 0.0)
      std::cout << fmt::format("elastic reference: at rest at t = {:.3g} s, u_el = {:.4g} m\n",
                               run.end_time, run.largest_displacement);
    else
      std::cout << fmt::format("F = {:.4f}: {:<8} {}\n", run.factor,
                               run.failing ? "failing" : "stable", run.reason);
    std::cout.flush();
  };
  const StrengthReductionResult result = find_factor_of_safety(description, options, directory);
  std::string picture;
  if (const ReductionRun* failing = result.first_failing(); failing && !result.interrupted) {
    picture = "mechanism.png";
    const int status =
        run_tool("plot_field.py", {failing->directory.string(), "--field", "eps_vp", "--magnify",
                                   "1", "-o", (directory / picture).string()});
    if (status != 0) {
      std::cerr << "rktsph: the mechanism picture could not be drawn (see above); fos.json is "
                   "written without it\n";
      picture.clear();
    }
  }
  {
    std::ofstream out(summary);
    out << strength_reduction_json(description, options, result, picture);
    if (!out) throw RunError("cannot write " + summary.string());
  }
  if (result.interrupted) {
    std::cerr << "rktsph: " << result.message << "\n";
    return interrupted_exit_status();
  }
  if (!result.bracket_holds) {
    std::cout << fmt::format("No factor of safety: {}. Runs: {}/ (fos.json)\n", result.message,
                             directory.string());
    return kExitValidationFailed;
  }
  std::cout << fmt::format(
      "Factor of safety F = {:.4f}, bracket [{:.4f}, {:.4f}] (stable at {:.4f}, failing at "
      "{:.4f}). Results: {}/ (fos.json{})\n",
      result.factor, result.stable, result.failing, result.stable, result.failing,
      directory.string(), picture.empty() ? "" : ", " + picture);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rktsph: Runge-Kutta Taylor SPH for the dynamics of dry and saturated soils"};
  app.set_version_flag("--version", std::string("rktsph ") + version_text());
  app.require_subcommand(1);

  std::string case_path, output;
  int threads = 0;
  std::vector<std::string> sets;
  bool quiet = false, overwrite = false;

  CLI::App* run = app.add_subcommand("run", "Run a case file and write its results");
  run->add_option("case", case_path, "Case file (YAML)")->required();
  run->add_option("-o,--output", output, "Output folder (default results/<case name>)");
  run->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(integer_in_range(1, 1024));
  run->add_option("--set", sets, "Override a case key: --set time.end=0.1 (repeatable)");
  run->add_flag("-q,--quiet", quiet, "No progress display");
  run->add_flag("--overwrite", overwrite,
                "Replace the results of an earlier run in the output folder (only rktsph's own "
                "files are removed)");
  std::string restart;
  run->add_option("--restart", restart,
                  "Continue the run in this folder from its last checkpoint (the case and --set "
                  "overrides must be those of that run)");
  SimulationLimits limits;
  const char* max_nodes_help =
      "Refuse a case whose geometry is estimated at more SPH nodes than this (default 1e7, "
      "about 35 GB)";
  run->add_option("--max-nodes", limits.max_nodes, max_nodes_help)->check(CLI::PositiveNumber);

  CLI::App* check = app.add_subcommand("check", "Validate a case file without running it");
  check->add_option("case", case_path, "Case file (YAML)")->required();
  check->add_option("--set", sets, "Override a case key (repeatable)");
  check->add_option("--max-nodes", limits.max_nodes, max_nodes_help)->check(CLI::PositiveNumber);
  check
      ->add_option("--threads", threads,
                   "OpenMP threads for building the stencils (default: all cores)")
      ->check(integer_in_range(1, 1024));
  std::string mesh_path;
  check->add_option("--write-mesh", mesh_path,
                    "Write the cells the case runs on to this Gmsh mesh file (MSH 2.2; 2D cases)");

  std::vector<std::string> names;
  bool all = false, quick = false, json = false;
  CLI::App* validate =
      app.add_subcommand("validate", "Run bundled validation cases against their references");
  validate->add_option("names", names, "Validation cases to run (default: all)");
  validate->add_flag("--all", all, "Run every bundled case");
  validate->add_flag("--quick", quick, "Coarser, shorter variants (as run by make test)");
  validate->add_flag("--json", json, "One JSON object per case per line");
  validate->add_option("-o,--output", output, "Folder for the runs (default results/validation)");
  validate->add_option("--set", sets,
                       "Override a key of the cases' files (repeatable); the references follow it, "
                       "the validation's own settings of its runs (the --quick lattice) win");
  validate
      ->add_option("--threads", threads,
                   "OpenMP threads of each case (default: the cores over the cases run at once)")
      ->check(integer_in_range(1, 1024));
  int jobs = 0;
  validate
      ->add_option("--jobs", jobs,
                   "Cases run at once (default: one per core when several are asked, else 1)")
      ->check(integer_in_range(1, 1024));
  std::string cases_option;
  validate->add_option("--cases", cases_option,
                       "Folder of the validation cases (default: RKTSPH_CASES, else the bundled "
                       "cases of the sources)");
  std::string report;
  validate->add_option("--report", report,
                       "Also write a report with plots to this folder (index.html, index.md); "
                       "the runs go there too. Needs python3-matplotlib");

  std::string run_directory, field;
  int component = -1;
  double plot_time = -1.0, magnification = 0.0;
  CLI::App* plot = app.add_subcommand(
      "plot", "Draw one output field of a run on its (deformed) particles to a PNG file");
  plot->add_option("run", run_directory, "Run folder (with series.pvd)")->required();
  plot->add_option("--field", field, "Field: stress, velocity, displacement, pressure, ...")
      ->required();
  plot->add_option("--component", component,
                   "Entry of the field's tuple (stress: 0 xx, 1 xy, 4 yy; velocity: 0 x, 1 y); "
                   "default: a scalar as is, a vector or tensor as its magnitude")
      ->check(CLI::Range(-1, 8));
  plot->add_option("--time", plot_time, "Output time to draw, nearest one [s] (default: last)");
  plot->add_option("--magnify", magnification,
                   "Draw particles at X + M u, X the reference position and u the displacement, "
                   "for every model (default 0: undeformed; 1: the current positions)");
  plot->add_option("-o,--output", output, "PNG file to write")->required();

  FosArguments fos_arguments;
  CLI::App* fos = app.add_subcommand(
      "fos", "Factor of safety by strength reduction: bisect the F dividing c' and tan phi'");
  fos->add_option("case", fos_arguments.case_path, "Case file (YAML)")->required();
  fos->add_option("-o,--output", fos_arguments.output,
                  "Output folder (default results/<case name>-fos)");
  fos->add_option("--bracket", fos_arguments.bracket,
                  "LOW HIGH: a stable and a failing strength factor (default 1 2)")
      ->expected(2)
      ->check(CLI::PositiveNumber);
  fos->add_option("--tolerance", fos_arguments.tolerance,
                  "Bisect until the bracket is this narrow (default 0.01)")
      ->check(CLI::PositiveNumber);
  fos->add_option("--rest-fraction", fos_arguments.criterion.rest_fraction,
                  "At rest: the largest speed at most this fraction of its peak (default 1e-3)")
      ->check(CLI::Range(0.0, 1.0));
  fos->add_option("--displacement-ratio", fos_arguments.criterion.displacement_ratio,
                  "Failing when the largest displacement exceeds this multiple of the elastic "
                  "one (default 10)")
      ->check(CLI::Range(1.0, 1e12));
  fos->add_option("--threads", threads, "OpenMP threads (default: all cores)")
      ->check(integer_in_range(1, 1024));
  fos->add_option("--set", fos_arguments.sets, "Override a case key (repeatable)");
  fos->add_flag("--overwrite", fos_arguments.overwrite,
                "Replace the results of an earlier strength reduction in the output folder");
  fos->add_flag("-q,--quiet", fos_arguments.quiet, "Print only the result");

  if (explain_missing_command(app, argc)) return kExitInput;
  if (reject_unknown_command(app, argc, argv)) return kExitInput;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    const int code = app.exit(error);
    return code == 0 ? 0 : kExitInput;
  }

  try {
    if (*run)
      return command_run(case_path, output, threads, sets, quiet, overwrite, restart, limits);
    if (*check) return command_check(case_path, sets, threads, limits, mesh_path);
    if (*validate)
      return command_validate(names, all, quick, json, output, report, threads, jobs, sets,
                              cases_option);
    if (*fos) {
      if (threads > 0) omp_set_num_threads(threads);
      return command_fos(fos_arguments);
    }
    if (*plot)
      return command_plot(run_directory, field, component, plot_time, magnification, output);
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
