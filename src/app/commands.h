// The command groups of the `rondo` binary. Each group lives in its own cmd_<group>.cpp and adds
// its subcommands to the root CLI11 app; cli.cpp calls every add_*_commands in turn.
//
// Contract for a command's callback: it writes results to ctx.out, diagnostics to ctx.err, and
// sets ctx.exit_code (0 ok, 1 the job failed, 2 bad input). Errors from libraries are reported
// through fail(), which picks the exit code from the error's kind.
#pragma once

#include <CLI/CLI.hpp>

#include <ostream>

#include "rondo/core/result.h"

namespace rondo::app {

struct CommandContext {
  std::ostream& out;
  std::ostream& err;
  int exit_code = 0;
};

// The exit code for an error: 2 for bad or missing input, 1 for everything else.
int exit_code_for(const Error& error);

// Prints "rondo: error: <message>" and records the exit code for it. Returns that code.
int fail(CommandContext& ctx, const Error& error);

void add_map_commands(CLI::App& root, CommandContext& ctx);
void add_task_commands(CLI::App& root, CommandContext& ctx);
void add_log_commands(CLI::App& root, CommandContext& ctx);
void add_schedule_commands(CLI::App& root, CommandContext& ctx);
void add_eval_commands(CLI::App& root, CommandContext& ctx);
void add_learn_commands(CLI::App& root, CommandContext& ctx);
void add_plan_commands(CLI::App& root, CommandContext& ctx);
void add_run_commands(CLI::App& root, CommandContext& ctx);
void add_serve_commands(CLI::App& root, CommandContext& ctx);
void add_backup_commands(CLI::App& root, CommandContext& ctx);

}  // namespace rondo::app
