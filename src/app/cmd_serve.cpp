// `rondo serve`: the executive as a service (serve_session.h, docs/api.md); with no file, the
// bundled G4S example on 127.0.0.1:8080 with its data in ./rondo-data.
#include <fmt/format.h>

#include <charconv>
#include <memory>

#include "commands.h"
#include "deployment.h"
#include "number_options.h"
#include "serve_session.h"

namespace rondo::app {
namespace {

struct ServeArgs {
  std::string deployment;
  std::string listen = "127.0.0.1:8080";
  std::string data = "rondo-data";
  std::string store;
  std::string token_file;
  double speed = 1.0;
  int streams = 64;
};

// "HOST:PORT", "[::1]:PORT"
Result<std::pair<std::string, int>> parse_listen(const std::string& text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0)
    return Error::invalid(fmt::format("--listen: expected HOST:PORT, found '{}'", text));
  std::string host = text.substr(0, colon);
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') host = host.substr(1, host.size() - 2);
  const std::string port_text = text.substr(colon + 1);
  int port = -1;
  const auto [end, err] = std::from_chars(port_text.data(), port_text.data() + port_text.size(), port);
  if (err != std::errc{} || end != port_text.data() + port_text.size() || port < 0 || port > 65535)
    return Error::invalid(fmt::format("--listen: the port '{}' is not from 0 (any free port) to 65535", port_text));
  return std::pair{host, port};
}

void run_serve(const ServeArgs& args, CommandContext& ctx) {
  auto listen = parse_listen(args.listen);
  if (!listen) return (void)fail(ctx, listen.error());
  const std::filesystem::path file =
      args.deployment.empty() ? default_deployment() : std::filesystem::path(args.deployment);
  auto deployment = load_deployment(file);
  if (!deployment) return (void)fail(ctx, deployment.error());
  std::optional<store::StoreLocation> store;
  if (!args.store.empty()) {
    auto where = store::StoreLocation::parse(args.store);
    if (!where) return (void)fail(ctx, where.error().with_context("--store"));
    store = std::move(*where);
  }
  ServeRequest request{
      .deployment = std::move(*deployment),
      .host = listen->first,
      .port = listen->second,
      .data = args.data,
      .store = std::move(store),
      .token_file = args.token_file.empty() ? std::nullopt : std::optional<std::filesystem::path>(args.token_file),
      .speed = args.speed,
      .max_streams = args.streams};
  if (Status ok = serve_deployment(request, ctx.err); !ok) return (void)fail(ctx, ok.error());
}

}  // namespace

void add_serve_commands(CLI::App& root, CommandContext& ctx) {
  auto args = std::make_shared<ServeArgs>();
  auto* serve = root.add_subcommand("serve", "Run the executive live with an HTTP API (default: the G4S example)");
  serve->add_option("deployment", args->deployment, "The deployment file (examples/g4s/deployment.yaml)");
  serve->add_option("--listen", args->listen, "HOST:PORT to listen on (default 127.0.0.1:8080; port 0: any free one)");
  serve->add_option("--data", args->data, "The data folder holding rondo.sqlite (default ./rondo-data)");
  serve->add_option("--store", args->store,
                    "The store: a postgresql:// URL (no password in it: password_file, PGPASSWORD or ~/.pgpass) or "
                    "an SQLite file; default: the deployment's store, else DATA/rondo.sqlite");
  serve->add_option("--token-file", args->token_file,
                    "A file (mode 600) holding the token every write must present as 'Authorization: Bearer'");
  serve->add_option("--speed", args->speed, "Run the clock X times faster than real time (default 1)");
  serve
      ->add_option("--streams", args->streams,
                   "At most N event streams (/api/v1/events) open at once (default 64; more get 503)")
      ->transform(whole_number(1, 4096));
  serve->callback([args, &ctx] { run_serve(*args, ctx); });
}

}  // namespace rondo::app
