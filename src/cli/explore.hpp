// SPDX-License-Identifier: GPL-3.0-or-later
// `btob explore`: the bifurcation diagram served to a browser.  The HTTP handlers (cmd_explore.cpp) only move bytes;
// what they serve is computed here in stages, each a function of typed input and output:
//
//   query parameters --parse_view--> View --compute--> bifurcation::Result --colour--> Image --encode_png--> PNG
//
// and the JSON answers (a served command's record, an orbit's tail, overlays, export).  Every parser throws
// core::InvalidField naming the parameter, the value and the accepted range (the server answers HTTP 400 with that
// line); nothing here reads a file, and export writes only into the folder it is given.
#pragma once

#include "bifurcation/bifurcation.hpp"
#include "core/request.hpp"

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace btob::cli::explore {

// A request's query parameters (the first value of each name).
using Params = std::map<std::string, std::string>;

// What one request may ask for.  A side of 4096 pixels is a 4K screen's width; the work budget bounds one image's
// map iterations (columns x initial conditions x iterations) to about a second of the batched kernel on 2 cores.
struct Limits {
  long max_side = 4096;
  double work_budget = 4e9;  // map iterations per image
  // The numbers of one /api/run answer: a million array elements is about 20 MB of JSON, what the page parses and
  // draws in about a second; a larger result is the command line's or Python's, which write HDF5.
  std::size_t max_answer_elements = 1000000;
};

// ---- stage 1: the view ------------------------------------------------------------------------------------------
// A view of the diagram: r window x coordinate window, the image's size, and the work per column.
struct View {
  double r_min = 0.0717, r_max = 0.1717;
  std::string coord = "theta";  // theta, phi, log10_theta, w1 or w2
  bool has_range = false;       // lo and hi given; else the coordinate's default range
  double lo = 0, hi = 0;
  long width = 1200, height = 700;  // pixels: r columns x coordinate bins
  long iterations = 2000, tail = 100;
  std::string grid = "paper";        // initial conditions of every column (the bifurcation command's grammar)
  std::vector<std::string> overlay;  // named overlays recorded in an exported scene
};
// Parses and validates a view; throws core::InvalidField naming the parameter.
View parse_view(const Params& p, const Limits& lim = {});
// The bifurcation request that computes a view (its scene reproduces it with `btob run`).
bifurcation::Request to_request(const View& v);

// ---- stage 2: compute -------------------------------------------------------------------------------------------
// The density of the view (bifurcation::run, cancelled through control.cancel).
bifurcation::Result compute(const View& v, const core::RunControl& control);

// ---- stage 3: colour --------------------------------------------------------------------------------------------
// An indexed image, row 0 at the top (the coordinate's hi), one byte per pixel into palette().
struct Image {
  long width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // [height, width]
};
// Index 0 is the background (no point); 1..255 a ramp from light to dark.
const std::vector<std::uint8_t>& palette();  // 256 RGB triples
// Each pixel's index is 1 + 254 log(1 + count) / log(1 + max count) (0 for an empty bin): log scale, since a
// column's counts span from single points of a chaotic band to whole tails on one periodic point.
Image colour(const bifurcation::Result& res);

// ---- stage 4: encode --------------------------------------------------------------------------------------------
// The PNG of an indexed image (libpng, colour-mapped: one byte per pixel to compress); `fast` trades size for speed.
std::string encode_png(const Image& img, bool fast);

// ---- the other answers -------------------------------------------------------------------------------------------
// GET /api/run?command=NAME&<field>=<value>...: a declared command (commands/commands.hpp) that its Spec marks
// `served`, its fields set from the query by their flag names through the parser of scenes and manifests
// (core::set_field), run through the one path of commands/execute.hpp (ready -> compute -> record) under `control`,
// and answered as the Record in JSON (record_json).  A name that is no served command, a parameter that is no field
// and a field the request refuses all throw core::InvalidField naming it; an answer of more than
// lim.max_answer_elements array elements throws std::length_error naming the limit.
std::string run_json(const Params& p, const core::RunControl& control, const Limits& lim = {});
// The served command `p` names (its "command" parameter), else core::InvalidField listing the served ones.
std::string served_command(const Params& p);
// GET /api/tail?r=&point=x,y,z&transient=&tail=: the orbit of `point` at r after `transient` steps, its next `tail`
// points in the strip (w1, w2), as {"w1": [...], "w2": [...]} (the orbit panel's picture; no request computes it).
std::string tail_json(const Params& p, const core::RunControl& control);
// GET /api/overlays?r_min=&r_max=: the lines of every overlay inside the window, by kind.
std::string overlays_json(const Params& p);
// POST /api/export?<view>: writes view-K.toml (a scene `btob run` reproduces) and view-K.png into `dir`, each
// atomically; returns their names and the view's point count as JSON.
std::string export_view(const View& v, const std::filesystem::path& dir);

// A one-line JSON error {"error": "..."}.
std::string error_json(const std::string& message);

}  // namespace btob::cli::explore
