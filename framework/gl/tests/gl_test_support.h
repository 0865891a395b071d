// Shared by the tests that need a GL context: one context per backend per test binary, created on
// first use (creating and destroying Mesa contexts repeatedly is slow and adds nothing).
#pragma once

#include <gtest/gtest.h>

#include <map>
#include <memory>

#include "shaderlab/gl/gl_context.h"

namespace shaderlab::testing {

inline GlContext* sharedContext(Backend backend, std::string* error) {
    static std::map<Backend, std::unique_ptr<GlContext>> contexts;
    static std::map<Backend, std::string> errors;
    auto it = contexts.find(backend);
    if (it == contexts.end()) {
        ContextResult r = createHeadlessContext(backend);
        errors[backend] = r.error;
        it = contexts.emplace(backend, std::move(r.context)).first;
    }
    *error = errors[backend];
    if (it->second && !it->second->makeCurrent()) {
        *error = std::string(backendName(backend)) + ": cannot make the context current again";
        return nullptr;
    }
    return it->second.get();
}

}  // namespace shaderlab::testing
