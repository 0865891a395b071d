// Private to shaderlab_classview: HTML text and the SVG plots of the class page. The plots are
// drawn here, element by element, so that the page needs no script and no library: each is an
// <svg> with a viewBox (it scales with the page) whose bars carry data- attributes with their
// numbers, for the browser test and for anyone reading the page's source.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "shaderlab/classview/class_report.h"

namespace shaderlab::classview {

// Text for HTML (element content and quoted attributes).
std::string escapeHtml(std::string_view s);
// Text from a student (a folder's name, a message): control characters and invalid UTF-8 made
// visible, then escaped.
std::string escapeUntrusted(std::string_view s);
// A relative path as a URL: each segment percent-encoded, '/' kept.
std::string urlPath(std::string_view path);
// At most `n` characters (UTF-8 code points), "…" added when cut.
std::string clipText(const std::string& s, std::size_t n);
// Letters, digits, '-', '_' and '.' kept, anything else '_' (ids and file names).
std::string safeName(const std::string& s);
// "50 %" for 0.5.
std::string percent(double share);
// A number of points, at most two decimals ("8", "8.5", "8.25").
std::string points(double v);

// The colour of a status on the page (lab and submission statuses), and of a goal's share.
const char* statusColor(const std::string& status);
const char* shareColor(double share);

// One row per goal: its title, a bar of the share met, "met / of · percent".
std::string goalSharesSvg(const std::vector<GoalShare>& goals);
// The statuses as one bar cut in proportion, each part with its count.
std::string statusBarSvg(const std::vector<StatusCount>& counts);
// Vertical bars of a histogram with its axes; `unit` names the x axis ("points").
std::string histogramSvg(const Histogram& h, const std::string& unit);
// A thin bar of `part` out of `whole`.
std::string smallBarSvg(int part, int whole, const char* color);

}  // namespace shaderlab::classview
