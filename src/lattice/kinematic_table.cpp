// The obstacle-free kinematic cost-to-go tables (see kinematic_table.h for what and why).
#include "amha_planner/lattice/detail/kinematic_table.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <stdexcept>
#include <thread>
#include <tuple>

#include "amha_planner/lattice/detail/heuristic_grids.h"
#include "amha_planner/lattice/lattice_config.h"
#include "amha_planner/lattice/motion_primitives.h"
#include "dial_queue.h"
#include "radix_heap.h"

namespace amha {
namespace lattice {

namespace {

/// The 8 rotations and reflections of the square grid, as integer matrices.
constexpr std::array<std::array<int, 4>, 8> kSquareSymmetries = {{
    {1, 0, 0, 1},
    {0, -1, 1, 0},
    {-1, 0, 0, -1},
    {0, 1, -1, 0},  // rotations by 0, 90, 180, 270
    {1, 0, 0, -1},
    {-1, 0, 0, 1},
    {0, 1, 1, 0},
    {0, -1, -1, 0},  // reflections: x axis, y axis, y = x, y = -x
}};

bool lessMove(const KinematicMove& a, const KinematicMove& b) {
  return std::tie(a.start_heading, a.end_heading, a.dx, a.dy, a.cost) <
         std::tie(b.start_heading, b.end_heading, b.dx, b.dy, b.cost);
}

/// The cheapest move per (displacement, headings), sorted: the action set as the table sees it.
std::vector<KinematicMove> canonicalMoves(std::vector<KinematicMove> moves) {
  std::sort(moves.begin(), moves.end(), lessMove);
  std::vector<KinematicMove> out;
  for (const KinematicMove& m : moves) {
    if (!out.empty() && out.back().dx == m.dx && out.back().dy == m.dy &&
        out.back().start_heading == m.start_heading && out.back().end_heading == m.end_heading) {
      continue;  // a costlier duplicate (sorted by cost last)
    }
    out.push_back(m);
  }
  return out;
}

constexpr int kAnyKey = -1;  // the entry key of kAnyHeading

}  // namespace

KinematicSlice::KinematicSlice(int radius, int num_headings)
    : radius_(radius), headings_(num_headings) {
  layOut();
}

KinematicSlice::KinematicSlice(int radius, int num_headings, const std::array<int, 4>& m,
                               const std::vector<int>& perm)
    : radius_(radius), headings_(num_headings), folded_(true), m_(m), perm_(perm) {
  // A reflection is I - 2 n n^T / |n|^2: a nonzero column of I - m points along n.
  n_ = {1 - m[0], -m[2]};
  if (n_[0] == 0 && n_[1] == 0) n_ = {-m[1], 1 - m[3]};
  layOut();
}

void KinematicSlice::layOut() {
  const int radius = radius_;
  row_start_.assign(static_cast<std::size_t>(2 * radius + 2), 0);
  lo_.assign(static_cast<std::size_t>(2 * radius + 1), 0);
  for (int dy = -radius; dy <= radius; ++dy) {
    const std::size_t row = static_cast<std::size_t>(dy + radius);
    // The largest w with w^2 + dy^2 <= R^2 (integers, so no rounding doubt).
    int w = static_cast<int>(
        std::sqrt(static_cast<double>(radius) * radius - static_cast<double>(dy) * dy));
    while (w * w + dy * dy > radius * radius) --w;
    while ((w + 1) * (w + 1) + dy * dy <= radius * radius) ++w;
    int lo = -w, hi = w;
    if (folded_) {  // n . (x, dy) >= 0 with n a multiple of (1, 0), (0, 1), (1, 1) or (1, -1)
      while (lo <= hi && !kept(lo, dy)) ++lo;
      while (hi >= lo && !kept(hi, dy)) --hi;
    }
    lo_[row] = lo;
    row_start_[row + 1] = row_start_[row] + static_cast<std::uint32_t>(hi >= lo ? hi - lo + 1 : 0);
  }
}

std::size_t KinematicSlice::bytes() const {
  return values_.capacity() * sizeof(std::uint16_t) +
         row_start_.capacity() * sizeof(std::uint32_t) + lo_.capacity() * sizeof(std::int32_t) +
         perm_.capacity() * sizeof(int);
}

struct KinematicTables::Entry {
  Direction direction;
  int key;  // canonical heading, or kAnyKey
  std::shared_future<std::shared_ptr<const KinematicSlice>> slice;
};

KinematicTables::KinematicTables(std::vector<KinematicMove> moves,
                                 std::vector<double> heading_angles, double cost_per_cell,
                                 int radius_cells)
    : moves_(canonicalMoves(std::move(moves))),
      angles_(std::move(heading_angles)),
      s_(cost_per_cell) {
  headings_ = static_cast<int>(angles_.size());
  if (headings_ <= 0) throw std::invalid_argument("kinematic table: no headings");
  if (!(s_ > 0.0) || !std::isfinite(s_))
    throw std::invalid_argument("kinematic table: cost per cell must be positive");
  if (radius_cells < 1)
    throw std::invalid_argument("kinematic table: the radius must be at least one cell");
  for (const KinematicMove& m : moves_) {
    if (m.start_heading < 0 || m.start_heading >= headings_ || m.end_heading < 0 ||
        m.end_heading >= headings_ || m.cost < 1) {
      throw std::invalid_argument("kinematic table: a move with an invalid heading or cost");
    }
  }
  // Entries hold values up to 2 s R (the cap G at the goal) and 0xFFFF means "not reached".
  const double max_radius = (65533.0 / (2.0 * s_));
  radius_ = static_cast<int>(std::min<double>(radius_cells, std::floor(max_radius)));
  // At most ~2^26 entries (128 MB) a slice, whatever the resolution asks for.
  radius_ = std::min(radius_, static_cast<int>(std::sqrt(6.7e7 / (M_PI * headings_))));
  if (radius_ < 1)
    throw std::invalid_argument("kinematic table: costs too large for a table of one cell");
  identity_perm_.resize(static_cast<std::size_t>(headings_));
  for (int h = 0; h < headings_; ++h) identity_perm_[static_cast<std::size_t>(h)] = h;
  // The square's symmetries that map headings onto headings and moves onto moves (costs equal).
  for (const std::array<int, 4>& m : kSquareSymmetries) {
    Symmetry sym{m, std::vector<int>(static_cast<std::size_t>(headings_), -1)};
    bool ok = true;
    for (int h = 0; h < headings_ && ok; ++h) {
      const double c = std::cos(angles_[h]), s = std::sin(angles_[h]);
      const double a = std::atan2(m[2] * c + m[3] * s, m[0] * c + m[1] * s);
      for (int j = 0; j < headings_; ++j) {
        if (angleDistance(angles_[j], a) < 1e-6) sym.perm[static_cast<std::size_t>(h)] = j;
      }
      ok = sym.perm[static_cast<std::size_t>(h)] >= 0;
    }
    if (!ok) continue;
    std::vector<KinematicMove> mapped;
    mapped.reserve(moves_.size());
    for (const KinematicMove& mv : moves_) {
      mapped.push_back({m[0] * mv.dx + m[1] * mv.dy, m[2] * mv.dx + m[3] * mv.dy,
                        sym.perm[static_cast<std::size_t>(mv.start_heading)],
                        sym.perm[static_cast<std::size_t>(mv.end_heading)], mv.cost});
    }
    std::sort(mapped.begin(), mapped.end(), lessMove);
    if (mapped == moves_) symmetries_.push_back(std::move(sym));
  }
  if (symmetries_.empty() || symmetries_.front().m != kSquareSymmetries[0]) {
    throw std::logic_error("kinematic table: the identity is not a symmetry");
  }
}

std::shared_ptr<KinematicTables> KinematicTables::shared(const std::vector<KinematicMove>& moves,
                                                         const std::vector<double>& heading_angles,
                                                         double cost_per_cell, int radius_cells) {
  static std::mutex registry_mutex;
  static std::vector<std::weak_ptr<KinematicTables>> registry;
  auto fresh =
      std::make_shared<KinematicTables>(moves, heading_angles, cost_per_cell, radius_cells);
  std::lock_guard<std::mutex> lock(registry_mutex);
  registry.erase(
      std::remove_if(registry.begin(), registry.end(), [](const auto& w) { return w.expired(); }),
      registry.end());
  for (const auto& w : registry) {
    auto t = w.lock();
    if (t && t->moves_ == fresh->moves_ && t->angles_ == fresh->angles_ && t->s_ == fresh->s_ &&
        t->radius_ == fresh->radius_) {
      return t;
    }
  }
  registry.push_back(fresh);
  return fresh;
}

std::shared_ptr<const KinematicSlice> KinematicTables::buildSlice(Direction direction, int heading,
                                                                  const StopCondition* stop) const {
  // A reflection that fixes the heading (any one, for kAnyKey) halves the slice.
  const Symmetry* mirror = nullptr;
  for (const Symmetry& sym : symmetries_) {
    const bool reflection = sym.m[0] * sym.m[3] - sym.m[1] * sym.m[2] < 0;
    if (reflection && mirror == nullptr &&
        (heading == kAnyKey || sym.perm[static_cast<std::size_t>(heading)] == heading))
      mirror = &sym;
  }
  auto slice = mirror != nullptr
                   ? std::make_shared<KinematicSlice>(radius_, headings_, mirror->m, mirror->perm)
                   : std::make_shared<KinematicSlice>(radius_, headings_);
  const int R = radius_, nh = headings_;
  const std::size_t cells = slice->cells();
  slice->values_.assign(cells * static_cast<std::size_t>(nh), 0xFFFF);
  std::uint16_t* dist = slice->values_.data();
  // Searching to the goal follows the moves backwards (from a state to its predecessors).
  const bool to_goal = direction == Direction::kToGoal;
  std::vector<std::vector<KinematicMove>> by_heading(static_cast<std::size_t>(nh));
  for (const KinematicMove& m : moves_) {
    by_heading[static_cast<std::size_t>(to_goal ? m.end_heading : m.start_heading)].push_back(m);
  }
  const double limit = 2.0 * s_ * R;
  const double slack = 1e-9 * limit + 1e-6;
  // The offset of each cell of the disc, to decode popped states.
  std::vector<std::array<std::int16_t, 2>> offset(cells);
  slice->forEachCell([&](int x, int y) {
    offset[slice->index(x, y, 0) / static_cast<std::size_t>(nh)] = {static_cast<std::int16_t>(x),
                                                                    static_cast<std::int16_t>(y)};
  });
  Cost max_cost = 0;
  for (const KinematicMove& m : moves_) max_cost = std::max(max_cost, m.cost);
  // Dial's buckets hold a 4-byte state per entry (the radix heap 8): the queue is most of a
  // build's transient memory.
  auto search = [&](auto& queue) {
    auto seed = [&](int h) {
      const std::size_t i = slice->index(0, 0, h);
      dist[i] = 0;
      queue.push(0, static_cast<std::uint32_t>(i));
    };
    if (heading == kAnyKey) {
      for (int h = 0; h < nh; ++h) seed(h);
    } else {
      seed(heading);
    }
    for (std::uint32_t pops = 0; !queue.empty();) {
      const std::pair<std::uint32_t, std::uint32_t> top = queue.pop();
      const std::uint32_t d = top.first, i = top.second;
      if (d != dist[i]) continue;
      if ((++pops & 4095) == 0 && stop != nullptr && stop->requested()) return false;
      const int h = static_cast<int>(i % static_cast<std::uint32_t>(nh));
      const int x = offset[i / static_cast<std::uint32_t>(nh)][0],
                y = offset[i / static_cast<std::uint32_t>(nh)][1];
      for (const KinematicMove& m : by_heading[static_cast<std::size_t>(h)]) {
        const int px = to_goal ? x - m.dx : x + m.dx, py = to_goal ? y - m.dy : y + m.dy;
        if (!slice->inDisc(px, py)) continue;
        const std::uint64_t nd = static_cast<std::uint64_t>(d) + static_cast<std::uint64_t>(m.cost);
        // Only states with d + s |p| <= 2 s R can lie on a path the table needs (header).
        if (static_cast<double>(nd) +
                s_ * std::sqrt(static_cast<double>(px) * px + static_cast<double>(py) * py) >
            limit + slack) {
          continue;
        }
        int qx = px, qy = py, qh = to_goal ? m.start_heading : m.end_heading;
        if (slice->folded()) slice->canonical(&qx, &qy, &qh);
        const std::size_t j = slice->index(qx, qy, qh);
        if (nd < dist[j]) {
          dist[j] = static_cast<std::uint16_t>(nd);
          queue.push(static_cast<std::uint32_t>(nd), static_cast<std::uint32_t>(j));
        }
      }
    }
    return true;
  };
  bool complete;
  if (max_cost < 65536) {
    detail::DialQueue queue(static_cast<std::uint32_t>(max_cost));
    complete = search(queue);
  } else {
    detail::RadixHeap queue;
    complete = search(queue);
  }
  if (!complete) return nullptr;
  // A state on the mirror line is its mirror image's twin (canonical()): copy its cost there.
  if (slice->folded()) {
    slice->forEachCell([&](int x, int y) {
      if (slice->n_[0] * x + slice->n_[1] * y != 0) return;
      std::uint16_t* v = dist + slice->index(x, y, 0);
      for (int k = 0; k < nh; ++k) {
        int cx = x, cy = y, ch = k;
        slice->canonical(&cx, &cy, &ch);  // on the line: the same cell
        v[k] = v[ch];
      }
    });
  }
  // The cap: K = min(T, floor(G)) with G = s (2R - |p|).
  slice->forEachCell([&](int x, int y) {
    const double g =
        s_ * (2.0 * R - std::sqrt(static_cast<double>(x) * x + static_cast<double>(y) * y));
    const std::uint16_t cap = static_cast<std::uint16_t>(std::floor(g));
    std::uint16_t* v = dist + slice->index(x, y, 0);
    for (int k = 0; k < nh; ++k) v[k] = std::min(v[k], cap);
  });
  return slice;
}

KinematicLookup KinematicTables::lookup(Direction direction, int heading, const StopCondition* stop,
                                        double* seconds) const {
  const auto t_call = std::chrono::steady_clock::now();
  bool was_ready = false;
  // The symmetry that takes the query's heading to the smallest heading of its orbit.
  const Symmetry* sym = &symmetries_.front();
  int key = kAnyKey;
  if (heading != kAnyHeading) {
    if (heading < 0 || heading >= headings_)
      throw std::out_of_range("kinematic table: heading out of range");
    key = heading;
    for (const Symmetry& s : symmetries_) {
      const int c = s.perm[static_cast<std::size_t>(heading)];
      if (c < key) {
        key = c;
        sym = &s;
      }
    }
  }
  std::promise<std::shared_ptr<const KinematicSlice>> promise;
  std::shared_future<std::shared_ptr<const KinematicSlice>> future;
  std::shared_ptr<Entry> mine;
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      future = {};
      for (const auto& e : entries_) {
        if (e->direction == direction && e->key == key) future = e->slice;
      }
      was_ready =
          future.valid() && future.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
      if (!future.valid()) {
        mine = std::make_shared<Entry>(Entry{direction, key, promise.get_future().share()});
        entries_.push_back(mine);
      }
    }
    if (mine) break;
    // Another call builds it: wait, but not beyond our own stop.
    while (future.wait_for(std::chrono::milliseconds(2)) != std::future_status::ready) {
      if (stop != nullptr && stop->requested()) return {};
    }
    if (future.get()) break;
    // That build was stopped (and its entry removed): build it here.
  }
  std::shared_ptr<const KinematicSlice> slice;
  if (mine) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      slice = buildSlice(direction, key, stop);
    } catch (...) {
      promise.set_exception(std::current_exception());
      std::lock_guard<std::mutex> lock(mutex_);
      entries_.erase(std::remove(entries_.begin(), entries_.end(), mine), entries_.end());
      throw;
    }
    promise.set_value(slice);
    std::lock_guard<std::mutex> lock(mutex_);
    if (!slice) {
      entries_.erase(std::remove(entries_.begin(), entries_.end(), mine), entries_.end());
      return {};
    }
    build_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  } else {
    slice = future.get();
  }
  if (seconds != nullptr) {
    *seconds =
        was_ready
            ? 0.0
            : std::chrono::duration<double>(std::chrono::steady_clock::now() - t_call).count();
  }
  KinematicLookup out;
  out.slice_ = std::move(slice);
  out.m_ = sym->m;
  out.perm_ = heading == kAnyHeading ? identity_perm_.data() : sym->perm.data();
  out.r2_ = radius_ * radius_;
  return out;
}

bool KinematicTables::prepare(Direction direction, const StopCondition* stop,
                              unsigned threads) const {
  std::vector<int> keys;  // one heading per orbit
  for (int h = 0; h < headings_; ++h) {
    bool canonical = true;
    for (const Symmetry& s : symmetries_)
      canonical = canonical && s.perm[static_cast<std::size_t>(h)] >= h;
    if (canonical) keys.push_back(h);
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stopped{false};
  auto worker = [&] {
    for (std::size_t k; !stopped && (k = next.fetch_add(1)) < keys.size();) {
      if (!lookup(direction, keys[k], stop).valid()) stopped = true;
    }
  };
  if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> pool;
  for (std::size_t t = 1; t < std::min<std::size_t>(threads, keys.size()); ++t)
    pool.emplace_back(worker);
  worker();
  for (auto& t : pool) t.join();
  return !stopped;
}

std::size_t KinematicTables::bytes() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::size_t b = 0;
  for (const auto& e : entries_) {
    if (e->slice.wait_for(std::chrono::seconds(0)) == std::future_status::ready) {
      try {
        if (auto s = e->slice.get()) b += s->bytes();
      } catch (...) {
      }
    }
  }
  return b;
}

double KinematicTables::buildSeconds() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return build_seconds_;
}

int KinematicTables::slicesBuilt() const {
  std::lock_guard<std::mutex> lock(mutex_);
  int n = 0;
  for (const auto& e : entries_)
    n += e->slice.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
  return n;
}

}  // namespace lattice
}  // namespace amha
