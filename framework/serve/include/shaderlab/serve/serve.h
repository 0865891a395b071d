// `shaderlab serve`: the browser workbench. A local web server (cpp-httplib) for one lab of one
// student's folder: the page (compiled into the program), the state of the workbench
// (workbench.h) as JSON, its pictures as PNG, and a stream of Server-Sent Events that tells every
// open page when something changed. It binds 127.0.0.1 unless told otherwise.
#pragma once

#include <string>

#include "shaderlab/serve/workbench.h"

namespace shaderlab::serve {

struct ServeOptions {
    WorkbenchOptions workbench;
    std::string host = "127.0.0.1";
    int port = 8420;              // 0: any free port (printed)
    int max_connections = 128;    // handled at once; further clients wait to be accepted
    int max_event_streams = 16;   // pages listening for changes at once
    std::size_t max_body = 4096;  // of a request (the only body is the view's JSON)
};

// Serves until SIGINT or SIGTERM. Returns 0, or 2 when it cannot start (port in use, no render
// server).
int runServe(const ServeOptions& options);

}  // namespace shaderlab::serve
