// tessera view's HTTP module: the workflow routes (view_http_flow.h).
#include "view_http_flow.h"

namespace tessera::cli {

void add_flow_routes(httplib::Server& svr, ViewBackend& backend, std::size_t max_open) {
  svr.Get("/api/overview", [&backend](const httplib::Request&, httplib::Response& res) {
    std::string json;
    const int status = backend.overview(json);
    reply(res, status, json);
  });
  svr.Get("/api/download", [&backend](const httplib::Request& req, httplib::Response& res) {
    std::string mime, bytes, json;
    const int status =
        backend.download(req.get_param_value("id"), req.get_param_value("as"), mime, bytes, json);
    if (status != 200) return reply(res, status, json);
    res.set_content(bytes, mime.c_str());
  });
  // A file of the page's "open…" or dropped on it: its bytes, read through `max_open` as they
  // arrive (a chunked body has no length to check first).
  svr.Post("/api/open", [&backend, max_open](const httplib::Request& req, httplib::Response& res,
                                             const httplib::ContentReader& read) {
    std::string body;
    bool over = false;
    const bool ok = read([&](const char* data, std::size_t n) {
      if (body.size() + n > max_open) {
        over = true;
        return false;
      }
      body.append(data, n);
      return true;
    });
    if (over) return reply_and_close(res, 413, error_json("file too large"));
    if (!ok) return reply_and_close(res, 400, error_json("bad request: the body did not arrive"));
    std::string json;
    const int status = backend.open(req.get_param_value("name"), std::move(body), json);
    reply(res, status, json);
  });
}

}  // namespace tessera::cli
