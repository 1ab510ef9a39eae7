// The dashboard's routes: the page at / and its script and style, from the files embedded at build
// time. The page holds no token: it asks for one when a write needs it (sessionStorage).
#include "api.h"
#include "dashboard_files.h"

namespace rondo::service {
namespace {

Handler file_handler(const std::string& name) {
  return [name](Api&, const httplib::Request&) {
    for (const EmbeddedFile& f : dashboard_files())
      if (name == f.name) {
        Reply r;
        r.text = std::string(f.body);
        r.content_type = f.content_type;
        r.headers = {{"Content-Security-Policy", "default-src 'self'; style-src 'self'; script-src 'self'"},
                     {"X-Content-Type-Options", "nosniff"},
                     {"Cache-Control", "no-cache"}};
        return r;
      }
    return error_reply(404, "not_found", "no dashboard file " + name);
  };
}

}  // namespace

void add_dashboard_endpoints(std::vector<Endpoint>& routes) {
  routes.push_back({"GET", "/", false, file_handler("index.html")});
  routes.push_back({"GET", "/dashboard.js", false, file_handler("dashboard.js")});
  routes.push_back({"GET", "/dashboard.css", false, file_handler("dashboard.css")});
  routes.push_back({"GET", "/favicon.svg", false, file_handler("favicon.svg")});
}

}  // namespace rondo::service
