// The dashboard's files, embedded in the binary at build time (cmake/EmbedFiles.cmake).
#pragma once

#include <span>
#include <string_view>

namespace rondo::service {

struct EmbeddedFile {
  const char* name;          // "index.html"
  const char* content_type;  // "text/html; charset=utf-8"
  std::string_view body;
};

std::span<const EmbeddedFile> dashboard_files();

}  // namespace rondo::service
