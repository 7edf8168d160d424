#include "rigid/campaign/plan.hpp"

#include <algorithm>
#include <cstring>
#include <numeric>
#include <stdexcept>

namespace rigid::campaign {
namespace {

constexpr std::int8_t kInFlight = -1;

bool is_result(std::int8_t o) {
  return o == static_cast<std::int8_t>(scenario::CellOutcome::survived) ||
         o == static_cast<std::int8_t>(scenario::CellOutcome::overturned) ||
         o == static_cast<std::int8_t>(scenario::CellOutcome::failed);
}

}  // namespace

Plan::Plan(int objects, int records, int scales, int rotations, int stop_after, std::vector<double> record_cost)
    : objects_(objects), records_(records), scales_(scales), rotations_(rotations), stop_after_(stop_after) {
  if (objects < 1 || records < 1 || scales < 1 || rotations < 1 || stop_after < 0) {
    throw std::invalid_argument("campaign plan needs at least one object, record, scale and rotation");
  }
  const long n = long(objects) * records * scales * rotations;
  outcome_.assign(n, static_cast<std::int8_t>(scenario::CellOutcome::not_run));
  results_.assign(n, TaskResult{});
  overturned_.assign(std::size_t(objects) * records * scales, 0);
  cutoff_.assign(std::size_t(objects) * records, -1);
  order_.resize(n);
  std::iota(order_.begin(), order_.end(), 0L);
  record_cost.resize(records, 1.0);
  // lowest scales first (the stop rule needs them), longest records first within a scale
  std::stable_sort(order_.begin(), order_.end(), [&](long a, long b) {
    const Cell ca = cell(a), cb = cell(b);
    if (ca.scale != cb.scale) return ca.scale < cb.scale;
    if (record_cost[ca.record] != record_cost[cb.record]) return record_cost[ca.record] > record_cost[cb.record];
    return a < b;
  });
}

void set_message(TaskResult& r, std::string_view text) {
  const std::size_t n = std::min(text.size(), kTaskMessageBytes - 1);
  std::memcpy(r.message, text.data(), n);
  std::memset(r.message + n, 0, kTaskMessageBytes - n);
}

std::string message_of(const TaskResult& r) { return std::string(r.message, strnlen(r.message, kTaskMessageBytes)); }

Cell Plan::cell(long t) const { return job::CellGrid{objects_, records_, scales_, rotations_}.cell(t); }

bool Plan::available(long t) const {
  if (outcome_[t] != static_cast<std::int8_t>(scenario::CellOutcome::not_run)) return false;
  const Cell c = cell(t);
  const int cut = cutoff(c.object, c.record);
  return cut < 0 || c.scale < cut;
}

long Plan::task(const Cell& c) const { return job::CellGrid{objects_, records_, scales_, rotations_}.task(c); }

void Plan::update_cutoff(long t, std::int8_t before) {
  const auto overturned = static_cast<std::int8_t>(scenario::CellOutcome::overturned);
  const Cell c = cell(t);
  const std::size_t pair = std::size_t(c.object) * records_ + c.record;
  int& count = overturned_[pair * scales_ + c.scale];
  const bool was_full = count == rotations_;
  count += int(outcome_[t] == overturned) - int(before == overturned);
  if (stop_after_ == 0 || was_full == (count == rotations_)) return;
  // the first run of stop_after fully overturned scales ends the record
  int run = 0;
  cutoff_[pair] = -1;
  for (int s = 0; s < scales_; ++s) {
    run = overturned_[pair * scales_ + s] == rotations_ ? run + 1 : 0;
    if (run == stop_after_) {
      cutoff_[pair] = s + 1;
      break;
    }
  }
}

void Plan::restore(const TaskResult& r) {
  if (r.task < 0 || r.task >= size()) return;
  if (!is_result(static_cast<std::int8_t>(r.outcome))) return;
  if (!is_result(outcome_[r.task])) {
    ++done_;
    if (r.outcome == static_cast<std::int32_t>(scenario::CellOutcome::failed)) ++failures_;
  }
  const std::int8_t before = outcome_[r.task];
  outcome_[r.task] = static_cast<std::int8_t>(r.outcome);
  results_[r.task] = r;
  if (before != outcome_[r.task]) update_cutoff(r.task, before);
}

std::optional<long> Plan::next() {
  while (!returned_.empty()) {
    const long t = returned_.back();
    returned_.pop_back();
    if (available(t)) {
      outcome_[t] = kInFlight;
      ++in_flight_;
      return t;
    }
  }
  while (cursor_ < order_.size()) {
    const long t = order_[cursor_++];
    if (available(t)) {
      outcome_[t] = kInFlight;
      ++in_flight_;
      return t;
    }
  }
  return std::nullopt;
}

void Plan::complete(const TaskResult& r) {
  if (r.task < 0 || r.task >= size()) return;
  if (outcome_[r.task] == kInFlight) --in_flight_;
  restore(r);
}

void Plan::release(long t) {
  if (t < 0 || t >= size() || outcome_[t] != kInFlight) return;
  outcome_[t] = static_cast<std::int8_t>(scenario::CellOutcome::not_run);
  --in_flight_;
  returned_.push_back(t);
}

bool Plan::finished() {
  if (in_flight_ > 0) return false;
  for (long t : returned_) {
    if (available(t)) return false;
  }
  // positions that are not available now never will be: step over them for good
  while (cursor_ < order_.size() && !available(order_[cursor_])) ++cursor_;
  return cursor_ == order_.size();
}

long Plan::remaining() const {
  long n = 0;
  for (int o = 0; o < objects_; ++o) {
    for (int r = 0; r < records_; ++r) {
      const int cut = cutoff(o, r);
      const int top = cut < 0 ? scales_ : cut;
      for (int s = 0; s < top; ++s) {
        for (int k = 0; k < rotations_; ++k) {
          n += outcome_[task({o, r, s, k})] == static_cast<std::int8_t>(scenario::CellOutcome::not_run);
        }
      }
    }
  }
  return n;
}

std::vector<bool> Plan::kept_mask() const {
  std::vector<bool> kept(outcome_.size(), false);
  for (int o = 0; o < objects_; ++o) {
    for (int r = 0; r < records_; ++r) {
      const int cut = cutoff(o, r);
      for (int s = 0; s < scales_; ++s) {
        for (int k = 0; k < rotations_; ++k) {
          const long t = task({o, r, s, k});
          kept[t] = is_result(outcome_[t]) && (cut < 0 || s < cut);
        }
      }
    }
  }
  return kept;
}

std::vector<std::int8_t> Plan::final_outcomes() const {
  std::vector<std::int8_t> out(outcome_.size(), static_cast<std::int8_t>(scenario::CellOutcome::not_run));
  for (int o = 0; o < objects_; ++o) {
    for (int r = 0; r < records_; ++r) {
      const int cut = cutoff(o, r);
      for (int s = 0; s < scales_; ++s) {
        for (int k = 0; k < rotations_; ++k) {
          const long t = task({o, r, s, k});
          if (cut >= 0 && s >= cut) {
            out[t] = static_cast<std::int8_t>(scenario::CellOutcome::inferred);
          } else if (is_result(outcome_[t])) {
            out[t] = outcome_[t];
          }
        }
      }
    }
  }
  return out;
}

}  // namespace rigid::campaign
