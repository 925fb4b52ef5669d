// SPDX-License-Identifier: GPL-3.0-or-later
// `btob explore`: the bifurcation diagram served to a browser.  The HTTP handlers (cmd_explore.cpp) only move bytes;
// what they serve is computed here in stages, each a function of typed input and output:
//
//   query parameters --parse_view--> View --compute--> bifurcation::Result --colour--> Image --encode_png--> PNG
//
// and the JSON answers (classify, basins, overlays, export).  Every parser throws core::InvalidField naming the
// parameter, the value and the accepted range (the server answers HTTP 400 with that line); nothing here reads a
// file, and export writes only into the folder it is given.
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
  double work_budget = 4e9;   // map iterations per image
  long max_basin_side = 300;  // basin grids up to 300 x 300 points
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
// GET /api/classify?r=&point=x,y,z[&tail=N]: the classification of one orbit (type, word, pattern, period, lambda1 and
// its error) and its last N points in the strip (w1, w2), as one JSON object.
std::string classify_json(const Params& p, const core::RunControl& control);
// GET /api/basins?r=&n=: the basins at r over an n x n sphere grid: labels and fractions with their intervals.
std::string basins_json(const Params& p, const core::RunControl& control, const Limits& lim = {});
// GET /api/overlays?r_min=&r_max=: the lines of every overlay inside the window, by kind.
std::string overlays_json(const Params& p);
// POST /api/export?<view>: writes view-K.toml (a scene `btob run` reproduces) and view-K.png into `dir`, each
// atomically; returns their names and the view's point count as JSON.
std::string export_view(const View& v, const std::filesystem::path& dir);

// A one-line JSON error {"error": "..."}.
std::string error_json(const std::string& message);

}  // namespace btob::cli::explore
