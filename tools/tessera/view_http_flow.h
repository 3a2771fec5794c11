// tessera view's HTTP module: the routes of an artist's workflow (the overview of every input,
// files opened or dropped on the page, downloads in other containers) and the reply helpers
// they share with view_http.cpp.
#pragma once

#include <httplib.h>

#include <cstddef>
#include <string>

#include "view_http.h"

namespace tessera::cli {

/// {"error": message}, the message's quotes escaped and anything outside printable ASCII
/// replaced.
std::string error_json(const std::string& message);
void reply(httplib::Response& res, int status, const std::string& json);
/// Replies and then closes the connection (for a request whose body is not read to its end).
void reply_and_close(httplib::Response& res, int status, const std::string& json);

/// GET /api/overview, POST /api/open?name=NAME (the file's bytes, read through `max_open`
/// as they stream: 413 past it) and GET /api/download?id=RESULT&as=KIND.
void add_flow_routes(httplib::Server& svr, ViewBackend& backend, std::size_t max_open);

}  // namespace tessera::cli
