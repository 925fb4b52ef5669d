// SPDX-License-Identifier: GPL-3.0-or-later
// What `btob particles` writes, computed here so that tests reach it: the CSV tables (through core::CsvTable; a
// value that is not a finite number is an empty cell), the manifest's attributes (describe) and the summary.
#include "particles/particles.hpp"

#include "core/csv.hpp"

#include <fmt/format.h>

#include <cmath>
#include <cstddef>

namespace btob::particles {

namespace {
std::string g15(double v) { return core::csv_number(v, "{:.15g}"); }
std::string g17(double v) { return core::csv_number(v); }
}  // namespace

std::vector<std::size_t> convergence_rows(std::size_t periods) {
  std::vector<std::size_t> rows;
  long next = 1;
  for (std::size_t n = 0; n < periods; ++n) {
    const long k = static_cast<long>(n) + 1;
    if (k < 100 || k >= next || n + 1 == periods) {
      rows.push_back(n);
      if (k >= 100) next = static_cast<long>(std::ceil(static_cast<double>(k) * std::pow(10.0, 0.05)));
    }
  }
  return rows;
}

const char* ParticlesResult::row_header() {
  return "word,r,periods,letters,sequence_ok,contraction,predicted,time_to_collapse";
}

std::string ParticlesResult::row() const {
  return fmt::format("{},{},{},{},{},{},{},{}", core::csv_text(word), r, periods, letters,
                     sequence_ok ? "true" : "false", g15(length_contraction), g15(length_predicted),
                     g15(time_to_collapse));
}

std::string ParticlesResult::row_csv(bool header) const {
  core::CsvTable t(row_header());
  t.line(row());
  return header ? t.text() : t.text().substr(t.text().find('\n') + 1);
}

std::string ParticlesResult::csv() const {
  core::CsvTable t(
      std::string(row_header()) +
      ",word_digits,outcome,periods_ok,velocity_contraction,velocity_predicted,time_contraction,time_predicted,"
      "length_spread,energy_ratio,collisions_unrescaled,collisions_limit_predicted,failure");
  t.line(row() + fmt::format(",{},{},{},{},{},{},{},{},{},{},{},{}", digits, core::csv_text(outcome), periods_ok,
                             g15(velocity_contraction), g15(velocity_predicted), g15(time_contraction),
                             g15(time_predicted), core::csv_number(length_spread, "{:.3g}"), g15(energy_ratio),
                             collisions_unrescaled, core::csv_number(collisions_limit_predicted, "{:.1f}"),
                             core::csv_text(failure)));
  return t.text();
}

std::string ParticlesResult::convergence_csv() const {
  core::CsvTable t("period,length_ratio,velocity_ratio,time_ratio");
  for (std::size_t n : convergence_rows(length_ratio.size()))
    t.line(fmt::format("{},{},{},{}", n + 1, g17(length_ratio[n]), g17(velocity_ratio[n]), g17(time_ratio[n])));
  return t.text();
}

namespace {
std::string letter_name(double code) {  // 0 start, 1 a, 2 b, 3 c
  const int l = static_cast<int>(code);
  return l == 0 ? "start" : std::string(1, static_cast<char>('a' + l - 1));
}
}  // namespace

std::string ParticlesResult::events_csv() const {
  core::CsvTable t("period,time,time_to_collapse,x1,x2,x3,x4,letter");
  for (std::size_t i = 0; i + 8 <= events.size(); i += 8)
    t.line(fmt::format("{},{},{},{},{},{},{},{}", static_cast<long>(events[i]), g17(events[i + 1]), g17(events[i + 2]),
                       g17(events[i + 3]), g17(events[i + 4]), g17(events[i + 5]), g17(events[i + 6]),
                       letter_name(events[i + 7])));
  return t.text();
}

void ParticlesResult::split_events() {
  event_period.clear();
  event_time.clear();
  event_time_to_collapse.clear();
  event_x.clear();
  event_letter.clear();
  for (std::size_t i = 0; i + 8 <= events.size(); i += 8) {
    event_period.push_back(static_cast<std::uint32_t>(events[i]));
    event_time.push_back(events[i + 1]);
    event_time_to_collapse.push_back(events[i + 2]);
    event_x.insert(event_x.end(), events.begin() + static_cast<std::ptrdiff_t>(i + 3),
                   events.begin() + static_cast<std::ptrdiff_t>(i + 7));
    event_letter.push_back(letter_name(events[i + 7]));
  }
}

void ParticlesResult::describe(core::Contents& c) const {
  const std::size_t N = length_ratio.size();
  c.array("length_ratio", length_ratio, {N}, "period", "1", "|p| after / before each period");
  c.array("velocity_ratio", velocity_ratio, {N}, "period", "1", "|q| after / before each period");
  c.array("time_ratio", time_ratio, {N}, "period", "1", "duration / previous duration (NaN for the first period)");
  const std::size_t E = event_period.size();
  c.array("event_period", event_period, {E}, "event", "1", "period of the event (0: the first), first periods only");
  c.array("event_time", event_time, {E}, "event", "|p0|/|q0|", "time since the start");
  c.array("event_time_to_collapse", event_time_to_collapse, {E}, "event", "|p0|/|q0|",
          "time left to the collapse (NaN without a collapse along the pattern)");
  c.array("event_x", event_x, {E, 4}, "event, particle", "|p0|",
          "positions x1..x4 in the centre-of-mass frame (collapse point 0)");
  c.text("event_letter", event_letter, "event", "letter",
         "the collision at the event: a, b or c (paper's letters), or start (the start of a period)");
  c.array("moduli", moduli, {moduli.size()}, "eigenvalue", "1", "moduli of the eigenvalues of M_w, decreasing");
  // JSON has no NaN or infinity: such values are recorded as the strings "nan", "inf".
  const auto num = [](double v) -> core::AttrValue {
    if (std::isfinite(v)) return v;
    return std::string(std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf"));
  };
  c.attr("word", word);
  c.attr("word_digits", digits);  // the word in digits 1, 2, 3 (not a precision)
  c.attr("letters", letters);
  c.attr("outcome", outcome);
  c.attr("r", r);
  c.attr("periods", periods);
  c.attr("periods_ok", periods_ok);
  c.attr("start", start);
  c.attr("sequence_ok", std::string(sequence_ok ? "true" : "false"));
  c.attr("length_contraction", num(length_contraction));
  c.attr("length_predicted", num(length_predicted));
  c.attr("velocity_contraction", num(velocity_contraction));
  c.attr("velocity_predicted", num(velocity_predicted));
  c.attr("time_contraction", num(time_contraction));
  c.attr("time_predicted", num(time_predicted));
  c.attr("time_to_collapse", num(time_to_collapse));
  c.attr("time_unit", std::string("|p0|/|q0| (unit gaps and unit relative velocities at the start)"));
  c.attr("collisions_unrescaled", collisions_unrescaled);
  c.attr("unrescaled_end", unrescaled_end);
  c.attr("collisions_limit_predicted", num(collisions_limit_predicted));
  c.attr("failure", failure);
  c.attr("seconds", seconds);
  c.attr("csv_empty_cells",
         std::string("contraction, predicted and the other ratios without a collapse or a full period (see failure); "
                     "time_to_collapse without a collapse along the pattern or when the durations do not shrink; "
                     "collisions_limit_predicted when the gaps never underflow; convergence.csv time_ratio of period "
                     "1 (no previous period); events.csv time_to_collapse without a collapse"));
}

std::string ParticlesResult::summary() const {
  return fmt::format(
      "btob: {} at r = {}: {} of {} periods reproduced ({} collisions per period); lengths x{:.12g} per period "
      "(predicted {:.12g}), velocities x{:.12g} ({:.12g}), times x{:.12g} ({:.12g}); collapse after {:.12g} |p0|/|q0|; "
      "without rescaling {} collisions ({}; predicted {:.0f}) ({:.2f} s)\n",
      word, r, periods_ok, periods, letters.size(), length_contraction, length_predicted, velocity_contraction,
      velocity_predicted, time_contraction, time_predicted, time_to_collapse, collisions_unrescaled, unrescaled_end,
      collisions_limit_predicted, seconds);
}

}  // namespace btob::particles
