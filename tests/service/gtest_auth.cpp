// Auth on and off: with a token every write needs it (401 without, 403 wrong), reads stay open;
// the token file must be private; a non-loopback host needs a token (the command exits 2).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <fstream>
#include <sstream>

#include "cli.h"
#include "live_service.h"
#include "test_files.h"

namespace rondo::test {
namespace {

constexpr const char* kToken = "s3cret-token-0123456789";

TEST(ApiAuth, WithATokenWritesNeedItAndReadsDoNot) {
  LiveService s(fresh_dir("rondo-service-test", "auth"), {.token = kToken});
  auto cli = s.client();
  auto none = cli.Post("/api/v1/tasks", s.task_body("a1"), "application/json");
  ASSERT_TRUE(none);
  EXPECT_EQ(none->status, 401);
  EXPECT_EQ(body_of(none)["error"]["code"], "unauthorized");
  auto wrong = cli.Post("/api/v1/tasks", {{"Authorization", "Bearer not-the-token-at-all"}}, s.task_body("a1"),
                        "application/json");
  EXPECT_EQ(wrong->status, 403);
  auto basic = cli.Post("/api/v1/tasks", {{"Authorization", std::string("Basic ") + kToken}}, s.task_body("a1"),
                        "application/json");
  EXPECT_EQ(basic->status, 403);
  EXPECT_EQ(cli.Post("/api/v1/tasks/a1/cancel", "", "application/json")->status, 401);
  EXPECT_EQ(cli.Delete("/api/v1/routines/x")->status, 401);
  EXPECT_EQ(body_of(cli.Get("/api/v1/tasks"))["total"], 0);  // nothing got in
  auto right = cli.Post("/api/v1/tasks", s.auth(), s.task_body("a1"), "application/json");
  EXPECT_EQ(right->status, 201) << right->body;
  EXPECT_EQ(cli.Get("/api/v1/tasks/a1")->status, 200);
}

TEST(ApiAuth, WithoutATokenWritesAreOpenOnLoopback) {
  LiveService s(fresh_dir("rondo-service-test", "open"));
  EXPECT_EQ(s.client().Post("/api/v1/tasks", s.task_body("o1"), "application/json")->status, 201);
}

std::filesystem::path write_token(const std::filesystem::path& dir, const std::string& text, mode_t mode) {
  const auto file = dir / "token";
  std::ofstream(file) << text;
  ::chmod(file.c_str(), mode);
  return file;
}

TEST(ApiAuth, TheTokenFileMustBePrivateAndHoldAToken) {
  const auto dir = fresh_dir("rondo-service-test", "token");
  auto ok = service::load_token_file(write_token(dir, std::string(kToken) + "\n", 0600));
  ASSERT_TRUE(ok.ok()) << ok.error().message;
  EXPECT_EQ(*ok, kToken);
  auto shared = service::load_token_file(write_token(dir, kToken, 0644));
  ASSERT_FALSE(shared.ok());
  EXPECT_NE(shared.error().message.find("read or written by others"), std::string::npos);
  EXPECT_FALSE(service::load_token_file(write_token(dir, "short", 0600)).ok());
  EXPECT_FALSE(service::load_token_file(dir / "missing").ok());
}

TEST(ApiAuth, ANonLoopbackHostWithoutATokenIsRefusedWithExitCode2) {
  EXPECT_TRUE(service::is_loopback_host("127.0.0.1"));
  EXPECT_TRUE(service::is_loopback_host("localhost"));
  EXPECT_TRUE(service::is_loopback_host("::1"));
  EXPECT_FALSE(service::is_loopback_host("0.0.0.0"));
  EXPECT_FALSE(service::is_loopback_host("192.168.1.4"));
  const auto dir = fresh_dir("rondo-service-test", "public");
  std::ostringstream out, err;
  const int code = app::run({"serve", "--listen", "0.0.0.0:18080", "--data", (dir / "data").string()}, out, err);
  EXPECT_EQ(code, 2);
  EXPECT_NE(err.str().find("needs --token-file"), std::string::npos) << err.str();
  EXPECT_FALSE(std::filesystem::exists(dir / "data" / "rondo.sqlite"));  // refused before anything was written
  std::ostringstream out2, err2;
  EXPECT_EQ(app::run({"serve", "--listen", "127.0.0.1:99999"}, out2, err2), 2);
  std::ostringstream out3, err3;
  EXPECT_EQ(
      app::run({"serve", "--listen", "127.0.0.1:18080", "--speed", "0", "--data", (dir / "d2").string()}, out3, err3),
      2);
}

}  // namespace
}  // namespace rondo::test
