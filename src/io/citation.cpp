// SPDX-License-Identifier: GPL-3.0-or-later
// The three renderings of one citation record (citation.hpp).  The paper's record holds what its LaTeX source
// states: title and authors; it names no venue, year or arXiv number, so none is written (never guessed).
#include "io/citation.hpp"

#include <btob/build_info.hpp>

#include <fmt/format.h>

#include <stdexcept>

namespace btob::io {
namespace {

constexpr const char* kTitle =
    "btob: a statistics lab for the b-to-b map of four one-dimensional inelastic hard spheres";
constexpr const char* kAuthors = "the btob developers";
constexpr const char* kLicense = "GPL-3.0-or-later";
constexpr const char* kAbstract =
    "btob iterates the b-to-b map P_r of four one-dimensional inelastic hard spheres (the spherical billiard "
    "reduction of Castorrini and Dolmaire) in float, double, long double, float128 or MPFR precision, and runs its "
    "analyses: bifurcation diagrams, Lyapunov exponents, attractors and their basins, periodic patterns, stability "
    "windows, correlations and the transfer operator, from a command line, a Python package and MPI sweeps.";
constexpr const char* kPaperTitle =
    "Four collapsing one-dimensional particles: a dynamical system approach of the spherical billiard reduction";

struct Person {
  const char* given;
  const char* given_bibtex;  // BibTeX's ASCII spelling of the accents
  const char* family;
};
constexpr Person kPaperAuthors[] = {{"Roberto", "Roberto", "Castorrini"}, {"Théophile", "Th{\\'e}ophile", "Dolmaire"}};

// "git commit C" (+ ", with uncommitted changes" when the build had some): what names the code that ran.
std::string commit_note(const std::string& commit, const std::string& dirty) {
  return fmt::format("git commit {}{}", commit, dirty == "yes" ? ", with uncommitted changes" : "");
}

std::string bibtex(const std::string& version, const std::string& commit, const std::string& dirty) {
  std::string paper_authors;
  for (const Person& p : kPaperAuthors)
    paper_authors += fmt::format("{}{}, {}", paper_authors.empty() ? "" : " and ", p.family, p.given_bibtex);
  // {btob} keeps the name's case under styles that lower-case titles; {{...}} keeps the authors one name.
  return fmt::format(
      "% btob {0}: please cite the software and the paper whose b-to-b map it implements.\n"
      "@software{{btob,\n"
      "  author = {{{{{1}}}}},\n"
      "  title = {{{{btob}}{2}}},\n"
      "  version = {{{0}}},\n"
      "  note = {{Version {0}, {3}}},\n"
      "  license = {{{4}}},\n"
      "}}\n"
      "@misc{{castorrini_dolmaire,\n"
      "  author = {{{5}}},\n"
      "  title = {{{6}}},\n"
      "}}\n",
      version, kAuthors, std::string(kTitle).substr(4), commit_note(commit, dirty), kLicense, paper_authors,
      kPaperTitle);
}

std::string cff(const std::string& version, const std::string& commit, const std::string& dirty) {
  std::string out = fmt::format(
      "# Citation File Format (https://citation-file-format.github.io): `btob cite --format cff` prints this with\n"
      "# the build's git commit; `btob cite` prints BibTeX.\n"
      "cff-version: 1.2.0\n"
      "message: \"If you use btob, please cite the software (its version) and the paper whose b-to-b map it "
      "implements.\"\n"
      "type: software\n"
      "title: \"{}\"\n"
      "abstract: \"{}\"\n"
      "authors:\n"
      "  - name: \"{}\"\n"
      "version: \"{}\"\n",
      kTitle, kAbstract, kAuthors, version);
  if (!commit.empty())
    out += fmt::format("commit: \"{}\"{}\n", commit, dirty == "yes" ? "  # with uncommitted changes" : "");
  out += fmt::format(
      "license: {}\n"
      "keywords:\n"
      "  - inelastic collapse\n"
      "  - inelastic hard spheres\n"
      "  - billiards\n"
      "  - dynamical systems\n"
      "  - Lyapunov exponents\n"
      "references:\n"
      "  - type: generic\n"
      "    title: \"{}\"\n"
      "    authors:\n",
      kLicense, kPaperTitle);
  for (const Person& p : kPaperAuthors)
    out += fmt::format("      - family-names: \"{}\"\n        given-names: \"{}\"\n", p.family, p.given);
  return out;
}

std::string text(const std::string& version, const std::string& commit, const std::string& dirty) {
  std::string paper_authors;
  for (std::size_t i = 0; i < std::size(kPaperAuthors); ++i) {
    const Person& p = kPaperAuthors[i];
    paper_authors += fmt::format("{}{}. {}", i == 0 ? "" : " and ", std::string(p.given).substr(0, 1), p.family);
  }
  return fmt::format("{}, {}, version {} ({}), licence {}.\n{}, \"{}\" (the paper whose b-to-b map btob implements).\n",
                     kAuthors, kTitle, version, commit_note(commit, dirty), kLicense, paper_authors, kPaperTitle);
}

}  // namespace

const std::vector<std::string>& citation_formats() {
  static const std::vector<std::string> formats{"bibtex", "cff", "text"};
  return formats;
}

std::string citation(const std::string& format, const std::string& version, const std::string& commit,
                     const std::string& dirty) {
  if (format == "bibtex") return bibtex(version, commit, dirty);
  if (format == "cff") return cff(version, commit, dirty);
  if (format == "text") return text(version, commit, dirty);
  throw std::invalid_argument(fmt::format("format: got '{}', expected one of bibtex, cff, text", format));
}

std::string citation(const std::string& format) {
  return citation(format, build::version, build::git_commit, build::git_dirty);
}

}  // namespace btob::io
