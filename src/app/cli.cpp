#include "cli.h"

#include <unistd.h>

#include <cstdlib>
#include <exception>
#include <new>

#include "commands.h"

#ifndef RONDO_VERSION
#define RONDO_VERSION "unknown"
#endif

namespace rondo::app {

int exit_code_for(const Error& error) {
  switch (error.code) {
    case ErrorCode::kInvalidInput:
    case ErrorCode::kNotFound:
    case ErrorCode::kConflict:
      return 2;
    default:
      return 1;
  }
}

int fail(CommandContext& ctx, const Error& error) {
  ctx.err << "rondo: error: " << error.message << '\n';
  ctx.exit_code = exit_code_for(error);
  return ctx.exit_code;
}

int run_guarded(const std::function<int()>& body, std::ostream& err) {
  try {
    return body();
  } catch (const std::bad_alloc&) {
    // Nothing here allocates: the message is a literal.
    err << "rondo: error: out of memory (the input may be too large for this machine)\n";
  } catch (const std::exception& e) {
    err << "rondo: internal error: " << e.what() << '\n';
  } catch (...) {
    err << "rondo: internal error: unknown exception\n";
  }
  return 1;
}

namespace {
[[noreturn]] void on_terminate() {
  // Called for an exception that escapes a thread, or a noexcept function: say what, exit 1.
  const char* what = "unknown exception";
  if (auto current = std::current_exception()) {
    try {
      std::rethrow_exception(current);
    } catch (const std::bad_alloc&) {
      what = "out of memory";
    } catch (const std::exception& e) {
      what = e.what();
    } catch (...) {
    }
  } else {
    what = "terminated without an exception";
  }
  const char prefix[] = "rondo: internal error: ";
  (void)!::write(STDERR_FILENO, prefix, sizeof prefix - 1);
  (void)!::write(STDERR_FILENO, what, std::char_traits<char>::length(what));
  (void)!::write(STDERR_FILENO, "\n", 1);
  std::_Exit(1);
}
}  // namespace

void install_terminate_handler() {
  std::set_terminate(on_terminate);
}

int run(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  return run_guarded([&] { return run_commands(args, out, err); }, err);
}

int run_commands(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  CommandContext ctx{out, err};
  CLI::App app{"rondo: a long-term task executive for mobile service robots", "rondo"};
  app.set_version_flag("--version", std::string("rondo ") + RONDO_VERSION);
  app.require_subcommand(1);
  app.footer("Exit codes: 0 ok, 1 the job failed, 2 bad input.\nRun 'rondo COMMAND --help' for a command's options.");

  add_map_commands(app, ctx);
  add_task_commands(app, ctx);
  add_log_commands(app, ctx);
  add_schedule_commands(app, ctx);
  add_eval_commands(app, ctx);
  add_learn_commands(app, ctx);
  add_plan_commands(app, ctx);
  add_run_commands(app, ctx);
  add_serve_commands(app, ctx);
  add_backup_commands(app, ctx);

  // CLI11 wants argv with the program name first and parses from the back.
  std::vector<std::string> reversed(args.rbegin(), args.rend());
  try {
    app.parse(std::move(reversed));
  } catch (const CLI::CallForHelp&) {
    out << app.help();
    return 0;
  } catch (const CLI::CallForAllHelp&) {
    out << app.help("", CLI::AppFormatMode::All);
    return 0;
  } catch (const CLI::CallForVersion&) {
    out << "rondo " << RONDO_VERSION << '\n';
    return 0;
  } catch (const CLI::ParseError& e) {
    // Bad command-line input is bad input: exit code 2 with CLI11's message naming the option.
    err << "rondo: error: " << e.what() << "\nRun 'rondo --help' for usage.\n";
    return 2;
  }
  return ctx.exit_code;
}

}  // namespace rondo::app
