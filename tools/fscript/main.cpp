// fscript: the FScript command-line tool (README.md, and the contract in ../shared/spec/cli.md).
// Every command runs on a thread with a large stack: deep but legal nesting never overflows.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <iostream>

#include "runtime/support/big_stack.h"
#include "tools/budget_flags.h"
#include "tools/cli_suggest.h"
#include "tools/limit_flags.h"
#include "tools/fscript/commands.h"
#include "tools/fscript/probe.h"
#include "tools/fscript/profile.h"
#include "tools/fscript/repl.h"
#include "runtime/support/version.h"

namespace fscript::cli {
namespace {

// The REPL needs a terminal and line editing (libedit): not in the browser build.
int repl(const Options& o) {
#if defined(FS_HAVE_REPL)
  return run_repl(o);
#else
  (void)o;
  std::cerr << "error: the REPL is not in the browser build; run a file: fscript run FILE\n";
  return 2;
#endif
}

struct Args {
  Options opts;
  std::string file, entry, points_path, size, bounds, out, passes, at, box;
  std::vector<std::string> files, values;
  size_t points = 1'000'000;
  unsigned threads = 1, repeat = 1;
  bool opt = false, gradient = false, one_point = false, grid = false, llvm = false, disk_cache = false,
       no_prune = false, stats = false;
  bool in_place = false, check_only = false;
  uint32_t max_depth = 1000;
  tools::RunLimits limits;
  Render3dArgs r3d;
  ProfileArgs profile;
};

void add_budget_flags(CLI::App& app, Args& a) { tools::add_budget_flags(app, a.opts.budgets, a.max_depth); }

CLI::App* add_compiling(CLI::App& app, const char* name, const char* help, Args& a) {
  CLI::App* c = app.add_subcommand(name, help);
  c->add_option("FILE", a.file, "the .fs script ('-' for standard input)")->required();
  c->add_option("--backend,-b", a.opts.backend,
                "evaluation backend: auto (the VM at once, native code from a background compile when the job is big "
                "enough), vm, sse or llvm (default: auto)");
  c->add_flag("--llvm-disk-cache", a.disk_cache,
              "keep the llvm backend's machine code in ~/.cache/fscript/llvm for the next run");
  c->add_option("--entry,-e", a.entry, "function to call (default: the script's entry point)");
  add_budget_flags(*c, a);
  tools::add_limit_flags(*c, a.limits);
  return c;
}

int dispatch(CLI::App& app, Args& a) {
  a.opts.budgets.max_call_depth = a.max_depth;
  if (std::string message; a.disk_cache && !backends::enable_llvm_disk_cache(message)) {
    std::cerr << "error: " << message << "\n";
    return 2;
  }
  // The REPL is a session, not a run: no watchdog there (the memory cap still holds).
  bool session = app.got_subcommand("repl") || (app.get_subcommands().empty() && isatty(STDIN_FILENO));
  if (!tools::apply_limits("fscript", a.limits, !session)) return kExitInput;
  if (CLI::App* run = app.get_subcommand("run"); run->parsed()) {
    a.values = run->remaining();
    return cmd_run(a.opts, a.file, a.entry, a.values);
  }
  if (app.got_subcommand("eval")) return cmd_eval(a.opts, a.file, a.entry, a.points_path);
  if (app.got_subcommand("check")) return cmd_check(a.files);
  if (app.got_subcommand("probe")) return cmd_probe(a.file, a.entry, a.at, a.box);
  if (app.got_subcommand("profile")) return a.profile.budgets = a.opts.budgets, cmd_profile(a.profile);
  if (app.got_subcommand("emit-ir")) return cmd_emit_ir(a.file, a.entry, a.opt, a.passes, a.llvm, a.gradient);
  if (app.got_subcommand("emit-asm")) return cmd_emit_asm(a.opts, a.file, a.entry);
  if (app.got_subcommand("fmt")) return cmd_fmt(a.file, a.in_place, a.check_only);
  if (app.got_subcommand("repl")) return repl(a.opts);
  if (app.got_subcommand("bench"))
    return cmd_bench(a.opts, a.file, a.entry, a.points, a.threads,
                     a.one_point  ? BenchPath::OnePoint
                         : a.grid ? BenchPath::Grid
                                  : BenchPath::Batch);
  if (app.got_subcommand("render3d")) {
    a.r3d.file = a.file, a.r3d.entry = a.entry, a.r3d.size = a.size, a.r3d.out = a.out;
    a.r3d.threads = a.threads, a.r3d.repeat = a.repeat, a.r3d.prune = !a.no_prune, a.r3d.stats = a.stats;
    if (!a.bounds.empty()) a.r3d.bounds = a.bounds;
    return cmd_render3d(a.opts, a.r3d);
  }
  if (app.got_subcommand("render2d"))
    return cmd_render2d(a.opts, a.file, a.entry, a.size, a.bounds, a.out, a.threads, !a.no_prune, a.stats, a.repeat);
  // No subcommand: the REPL on a terminal; otherwise the program on standard input runs once.
  if (isatty(STDIN_FILENO)) return repl(a.opts);
  return cmd_run(a.opts, "-", a.entry, {});
}

int real_main(int argc, char** argv) {
  CLI::App app{"fscript: compiler, runner and tools for FScript, the function-script language of FVRML"};
  app.set_version_flag("--version", fscript::support::version_line("fscript"));
  app.require_subcommand(0, 1);
  Args a;
  add_budget_flags(app, a);
  tools::add_limit_flags(app, a.limits);

  CLI::App* run =
      add_compiling(app, "run", "call the entry (or --entry NAME) with numeric ARGs and print the result", a);
  // The arguments are the subcommand's extras, in their order: a positional option would take
  // "1" but leave "-inf" (not a number to the parser, so not a positional) to the extras, out of
  // order.
  run->allow_extras();
  run->footer("ARG...: the entry's arguments (nan, inf, -inf accepted); missing ones are 0");

  CLI::App* eval = add_compiling(app, "eval", "evaluate rows of comma-separated arguments in batches", a);
  eval->add_option("--points,-p", a.points_path, "file of rows ('-' or absent: standard input)");

  CLI::App* check = app.add_subcommand("check", "diagnostics only, for .fs scripts and .wrl scenes");
  check->add_option("FILE", a.files, "files to check")->required();

  CLI::App* probe = app.add_subcommand("probe", "every variable of the script at a point, or over a box");
  probe->add_option("FILE", a.file, "the .fs script")->required();
  probe->add_option("--entry,-e", a.entry, "function to probe (default: the script's entry point)");
  probe->add_option("--at", a.at, "the point: x,y,z[,t] (the entry's inputs, missing ones 0)");
  probe->add_option("--bound", a.box, "the box: x0,x1,y0,y1,z0,z1[,t0,t1]: intervals instead of values");

  CLI::App* profile = app.add_subcommand(
      "profile", "where a shape's evaluation goes while it is meshed: each line's share, pruning, a picture");
  profile->add_option("FILE", a.profile.file, "the .fs script or .wrl scene")->required();
  profile->add_option("--backend,-b", a.profile.backend, "evaluation backend: auto, vm, sse or llvm (default: auto)")
      ->check(CLI::IsMember({"auto", "vm", "sse", "llvm"}));
  profile->add_option("--threads,-j", a.profile.threads, "threads, 1 to 256 (default 1)")
      ->check(CLI::Range(1u, 256u).description(""));
  profile->add_option("--resolution-scale", a.profile.resolution_scale, "multiply every node's resolution by K")
      ->check(CLI::Range(1e-3, 1e3).description(""))
      ->type_name("K");
  profile
      ->add_option("--picture", a.profile.picture,
                   "a PNG of the box seen from +z: the work per column and the mean tape length")
      ->type_name("FILE.png");
  profile->add_flag("--json", a.profile.json, "the report as JSON");
  profile->add_flag("!--no-prune", a.profile.prune, "sample every grid point (what pruning saves, by comparison)");

  CLI::App* emit = app.add_subcommand("emit-ir", "print the SSA IR");
  emit->add_option("FILE", a.file, "the .fs script")->required();
  emit->add_flag("--opt", a.opt, "after the optimisation pipeline");
  emit->add_flag("--llvm", a.llvm, "the kernel lowered to LLVM IR and optimised by LLVM (the llvm backend)");
  emit->add_option("--passes", a.passes,
                   "run these passes in order instead (inline,promote,fold,dce,gvn,simplify,ifconv)");
  emit->add_option("--entry,-e", a.entry, "function to build the kernel for");
  emit->add_flag(
      "--gradient", a.gradient,
      "the optimised kernel of f and its partial derivatives in x, y, z (what the meshers evaluate for normals)");

  add_compiling(app, "emit-asm", "print the generated code of a backend", a);

  CLI::App* fmt = app.add_subcommand("fmt", "print the canonical formatting of a script");
  fmt->add_option("FILE", a.file, "the .fs script")->required();
  fmt->add_flag("-i,--in-place", a.in_place, "rewrite FILE in place instead of printing");
  fmt->add_flag("--check", a.check_only, "print nothing; exit 1 (naming FILE) if it is not formatted");

  CLI::App* repl = app.add_subcommand("repl", "the interactive session (also what fscript alone starts on a terminal)");
  repl->add_option("--backend,-b", a.opts.backend,
                   "the backend it starts with: auto, vm, sse or llvm (default: auto; :backend changes it)");
  add_budget_flags(*repl, a);
  app.footer(
      "With no command: on a terminal, the REPL (fscript repl); otherwise the program on standard\n"
      "input runs once (fscript < FILE). Exit status: 0 success, 1 an error in the input, 2 usage.");

  CLI::App* bench = add_compiling(app, "bench", "time the batch path over many points", a);
  bench->add_option("--points,-n", a.points, "number of points, at least 1 (default 1,000,000)")
      ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 32).description(""))
      ->type_name("N");
  bench->add_option("--threads,-j", a.threads, "threads, 1 to 1,024 (default 1)")
      ->check(CLI::Range(1u, 1024u).description(""))
      ->type_name("N");
  bench->add_flag("--one-point", a.one_point, "call the kernel one point at a time instead of in batches");
  bench
      ->add_flag("--grid", a.grid,
                 "evaluate the grid row by row (Kernel::eval_rows: what does not depend on x once per row)")
      ->excludes("--one-point");

  CLI::App* r2d = add_compiling(app, "render2d", "picture of f(x, y, 0, 0) >= 0 as a PNG", a);
  r2d->add_option("--size,-s", a.size, "W or WxH pixels")->required();
  r2d->add_option("--bounds", a.bounds, "X0,X1,Y0,Y1")->required();
  r2d->add_option("-o,--output", a.out, "output PNG");
  r2d->add_option("--threads,-j", a.threads, "threads, 1 to 1,024 (default 1)")
      ->check(CLI::Range(1u, 1024u).description(""))
      ->type_name("N");
  r2d->add_flag("--no-prune", a.no_prune, "evaluate every pixel (no interval pruning; the same picture, slower)");
  r2d->add_option("--repeat", a.repeat, "render N times and print the best time (benchmarks; default 1)")
      ->check(CLI::Range(1u, 1000u).description(""))
      ->type_name("N");
  r2d->add_flag("--stats", a.stats, "print how the quadtree went: regions per level, tape lengths, points evaluated");

  CLI::App* r3d =
      add_compiling(app, "render3d", "picture of the shape f(x, y, z, 0) >= 0 as a PNG, without meshing", a);
  r3d->add_option("--size,-s", a.size, "W or WxH pixels")->required();
  r3d->add_option("--bounds", a.bounds, "the box X0,X1,Y0,Y1,Z0,Z1 (default -1,1,-1,1,-1,1)");
  r3d->add_option("--view", a.r3d.view,
                  "AZIMUTH,ELEVATION in degrees: where the orthographic camera looks from (default 0,0: down -z, "
                  "x to the right, y up)");
  r3d->add_option("--steps", a.r3d.steps, "depth steps across the box, 2 to 65,536 (default: the larger side)")
      ->check(CLI::Range(2u, 65536u).description(""))
      ->type_name("N");
  r3d->add_option("--image", a.r3d.image, "shaded (default), depth (near is white) or normal (rgb = (n + 1) / 2)");
  r3d->add_option("-o,--output", a.out, "output PNG");
  r3d->add_option("--threads,-j", a.threads, "threads, 1 to 1,024 (default 1)")
      ->check(CLI::Range(1u, 1024u).description(""))
      ->type_name("N");
  r3d->add_flag("--no-prune", a.no_prune,
                "probe every step of every ray (no interval pruning; the same picture, slower)");
  r3d->add_option("--repeat", a.repeat, "render N times and print the best time (benchmarks; default 1)")
      ->check(CLI::Range(1u, 1000u).description(""))
      ->type_name("N");
  r3d->add_flag("--stats", a.stats, "print how the descent went: regions per level, points evaluated");

  if (std::string error; !tools::check_command_line(app, argc, argv, true, error)) {
    std::cerr << "error: " << error << "\nRun with --help for more information.\n";
    return kExitUsage;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitUsage;
  }
  return dispatch(app, a);
}

}  // namespace
}  // namespace fscript::cli

int main(int argc, char** argv) {
  fscript::support::prepare_huge_heap();  // before any thread: one heap for all
  fscript::support::set_default_thread_stack();  // workers' stacks not sized by ulimit -s
  int rc = 0;
  fscript::support::run_with_big_stack([&] { rc = fscript::cli::real_main(argc, argv); });
  std::cout.flush();
  return rc;
}
