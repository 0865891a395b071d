// The debug view of a scene's vertex data. A program the framework owns (shaders/debug_view.vert
// and .frag, compiled into the library) draws every mesh of a lab's scene with the scene's camera
// (the lab's camera override and the viewer's orbit applied, as for the lab's own image) and colours
// each fragment by one vertex attribute, so that a student or an author sees what a shader receives.
// It is reached through renderLab() (RenderOptions::debug_view), so the window, the page and
// `shaderlab render --debug` get it from one place, in the same child process as a lab's render.
//
// What it does not do: run any of the lab's passes or read a submission's files; light or shade
// anything; or make up data a file lacks. A mesh without a TANGENT attribute is drawn grey in the
// tangent views and a note says so, although lab shaders receive the MikkTSpace tangents the loader
// generates for it (docs/scenes.md); a mesh without TEXCOORD_0 is grey in the uv views.
#pragma once

#include <string>
#include <vector>

#include "shaderlab/lab/lab_spec.h"
#include "shaderlab/render/renderer.h"

namespace shaderlab {

struct DebugViewInfo {
    DebugView view;
    const char* name;   // the one word for it: command line, window, page, file names
    const char* label;  // what the colours mean, in one line
};

// Every view but Off, in the order menus list them.
const std::vector<DebugViewInfo>& debugViews();
// The entry of `view`; null for Off.
const DebugViewInfo* debugViewInfo(DebugView view);
// "off" for Off, else the view's name.
const char* debugViewName(DebugView view);
// "off" or a view's name; false (and `out` untouched) for anything else.
bool parseDebugView(const std::string& name, DebugView* out);
// The names, "off" first, joined with `separator` (for messages and --help).
std::string debugViewNames(const std::string& separator);

// The grey a mesh is drawn in when it lacks what the view shows. As n * 0.5 + 0.5 it would be a
// vector of length 0.52, so it is never taken for a unit direction, nor for a handedness colour.
constexpr float kDebugNeutral = 0.35f;
// The background where no mesh is drawn (coverage 0): the window's own backdrop.
constexpr float kDebugBackground[3] = {0.1f, 0.1f, 0.12f};

// What a pixel of `view`'s image stands for, in words and numbers: "normal (+0.000, +0.217, +0.976)",
// "handedness w = -1.000", "texture coordinates s = 0.2500, t = 0.7500", "grey: ...", or "no mesh
// here" where `covered` is false. For the window's and the page's pixel inspectors.
std::string describeDebugPixel(DebugView view, float r, float g, float b, bool covered);

// Draws `view` of every scene of `spec` (options.only_scenes when given; options.orbit turns the
// camera; the other options are not used) on the current GL context, at the size of the lab's
// final graded image. Each scene gets one image, RGBA with alpha 1 (an opaque picture): pass
// "debug", target "debug", attachment the view's name, graded false, coverage 1 where a mesh was drawn. What
// the view could not show comes as diagnostics of severity "note" naming the scene file and the mesh ("no
// tangents in scenes/sphere.gltf, mesh sphere: ..."); the loader's warnings come as "warning", as in
// renderLab.
LabRender renderDebugView(const LabSpec& spec, DebugView view, const RenderOptions& options);

}  // namespace shaderlab
