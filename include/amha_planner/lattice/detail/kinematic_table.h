// The obstacle-free kinematic cost-to-go of the lattice: for a goal state at the origin, the
// exact cost of the cheapest primitive sequence from (dx, dy, heading) to it on an empty map,
// within a disc of radius R cells, capped so that it stays consistent across the disc's edge.
// It knows what the 2-D heuristics cannot: that a robot facing away from its goal must loop.
//
// What is stored, and why it is consistent. Let T(s) be the exact cost-to-go on the infinite
// empty lattice, e(s) = s_c |s - goal| with s_c <= cost / |displacement| for every action (the
// Euclidean anchor, in cost units per cell) and G(s) = s_c (2R - |s - goal|). The table holds
//     K(s) = min(T(s), floor(G(s)))   for |s - goal| <= R,
// and the anchor takes max(its other terms, floor(e(s)), K(s)); outside the disc K is not
// looked up, which is the same as K(s) = floor(e(s)) there, since floor(G) <= floor(e) when
// |s - goal| >= R. So the anchor's table term is max(floor(e), min(T, floor(G))) everywhere:
//  - T is consistent: it is an exact distance on the empty lattice, a supergraph of any map's
//    lattice whose edges cost no more (a map only removes edges and adds cell-cost penalties);
//  - floor(G) is consistent: G changes by at most s_c |d| <= cost along an edge of
//    displacement d, and floor(a) - floor(b) <= ceil(a - b) <= cost (integers);
//  - min and max of consistent heuristics are consistent, and K is 0 at the goal itself
//    (T = 0 there), so it is also admissible.
// Computing T only inside the disc is exact where it matters: if T(s) <= G(s), every state p
// on a cheapest path from s has T(p) <= T(s) - s_c |s - p| <= 2 s_c R - s_c |p - goal| (each
// action costs at least s_c per cell of displacement), and with T(p) >= s_c |p - goal| this
// gives |p - goal| <= R: the path lies in the disc, so a Dijkstra confined to the disc finds
// T(s). Where T(s) > G(s) the confined Dijkstra's value is larger still and the cap gives
// G(s) either way. The same bound lets the Dijkstra skip any state p whose tentative cost d
// has d + s_c |p - goal| > 2 s_c R. The tests check K against an unconfined Dijkstra and the
// anchor's consistency on every edge, including the edges that cross the disc's edge.
//
// Symmetries: the rotations and reflections of the square grid that map the action set onto
// itself (same displacements, headings and costs) map cost-to-go onto cost-to-go, so one
// table per orbit of goal headings is enough (3 for the usual 16 headings instead of 16).
// A reflection that fixes the table's own goal heading (the x axis for heading 0, y = x for
// 45 degrees) maps the table onto itself: such a table keeps one half of the disc (the mirror
// line included) and reads the other half through the mirror, in half the memory. Its
// Dijkstra runs on the quotient graph: a state across the mirror is its mirror image, and a
// state on the line is one with its mirror image there (same cell, mirrored heading), whose
// cost-to-go is the same because the reflection fixes the goal state; the line's twins get
// their costs copied at the end.
//
// Tables are built on first use (a Dijkstra over about pi R^2 x headings states), shared by
// every query and every planner with the same actions (KinematicTables::shared), and a build
// honours a StopCondition.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <vector>

#include "amha_planner/search/stop_condition.h"
#include "amha_planner/search/types.h"

namespace amha {
namespace lattice {

struct KinematicTableTestAccess;  // the tests' mutations

/// What the table needs of an action: its displacement, headings and cost on a free cell.
struct KinematicMove {
  int dx = 0, dy = 0;
  int start_heading = 0, end_heading = 0;
  Cost cost = 1;
  bool operator==(const KinematicMove& o) const {
    return dx == o.dx && dy == o.dy && start_heading == o.start_heading &&
           end_heading == o.end_heading && cost == o.cost;
  }
};

/// One table: K over the disc for one canonical goal (or start) heading; over half of it when
/// a reflection fixes that heading (fold()).
class KinematicSlice {
 public:
  /// The whole disc.
  KinematicSlice(int radius, int num_headings);
  /// Half of it: the offsets p with n . p >= 0, n the normal of reflection m's mirror line;
  /// `perm` is m's action on headings (m must fix the slice's goal heading).
  KinematicSlice(int radius, int num_headings, const std::array<int, 4>& m,
                 const std::vector<int>& perm);
  int radius() const { return radius_; }
  bool folded() const { return folded_; }
  /// K at offset (dx, dy) from the goal with heading h; the offset must lie in the disc.
  std::uint16_t at(int dx, int dy, int h) const {
    if (!kept(dx, dy)) fold(&dx, &dy, &h);
    return values_[index(dx, dy, h)];
  }
  bool inDisc(int dx, int dy) const { return dx * dx + dy * dy <= radius_ * radius_; }
  /// Where a stored offset's entry is (the offset must be in the disc and the kept half).
  std::size_t index(int dx, int dy, int h) const {
    const std::size_t row = static_cast<std::size_t>(dy + radius_);
    return (row_start_[row] + static_cast<std::size_t>(dx - lo_[row])) * headings_ + h;
  }
  /// Cells stored (the whole disc's, or about half).
  std::size_t cells() const { return row_start_.back(); }
  std::size_t bytes() const;

 private:
  friend class KinematicTables;
  friend struct KinematicTableTestAccess;
  /// Maps a state of the dropped half onto its mirror image in the kept half.
  void fold(int* dx, int* dy, int* h) const {
    const int x = *dx, y = *dy;
    *dx = m_[0] * x + m_[1] * y;
    *dy = m_[2] * x + m_[3] * y;
    *h = perm_[static_cast<std::size_t>(*h)];
  }
  /// The state of the quotient that stands for (dx, dy, h), whose cost-to-go is the same: its
  /// mirror image if it lies in the dropped half; on the mirror line, of the state and its
  /// mirror image (same cell, headings h and perm h) the one with the smaller heading.
  void canonical(int* dx, int* dy, int* h) const {
    const int side = n_[0] * *dx + n_[1] * *dy;
    if (side < 0) {
      fold(dx, dy, h);
    } else if (side == 0 && perm_[static_cast<std::size_t>(*h)] < *h) {
      *h = perm_[static_cast<std::size_t>(*h)];
    }
  }
  /// True if (dx, dy) is stored: in the kept half (folded slices) or anywhere.
  bool kept(int dx, int dy) const { return !folded_ || n_[0] * dx + n_[1] * dy >= 0; }
  /// f(dx, dy) for every stored offset, in storage order.
  template <class F>
  void forEachCell(F&& f) const {
    for (int dy = -radius_; dy <= radius_; ++dy) {
      const std::size_t row = static_cast<std::size_t>(dy + radius_);
      const int end = lo_[row] + static_cast<int>(row_start_[row + 1] - row_start_[row]);
      for (int dx = lo_[row]; dx < end; ++dx) f(dx, dy);
    }
  }
  void layOut();

  int radius_, headings_;
  bool folded_ = false;
  std::array<int, 4> m_{1, 0, 0, 1};      // the mirror (folded slices)
  std::array<int, 2> n_{0, 0};            //   its normal: kept offsets have n . p >= 0
  std::vector<int> perm_;                 //   and its action on headings
  std::vector<std::uint32_t> row_start_;  // 2R + 2 entries: cells before each row (dy = -R ..)
  std::vector<std::int32_t> lo_;          // per row: the first stored dx (the run is contiguous)
  std::vector<std::uint16_t> values_;
};

/// A table placed for one query: the slice of the goal's orbit and the symmetry that maps the
/// query's offsets and headings onto it.
class KinematicLookup {
 public:
  KinematicLookup() = default;
  bool valid() const { return slice_ != nullptr; }
  int radius() const { return slice_->radius(); }
  /// K at offset (dx, dy) from the goal (searching backward: from the start) with heading h,
  /// or 0 outside the disc (where the Euclidean term says as much).
  std::uint32_t value(int dx, int dy, int h) const {
    if (dx * dx + dy * dy > r2_) return 0;
    const int tx = m_[0] * dx + m_[1] * dy, ty = m_[2] * dx + m_[3] * dy;
    return slice_->at(tx, ty, perm_[h]);
  }

 private:
  friend class KinematicTables;
  friend struct KinematicTableTestAccess;
  std::shared_ptr<const KinematicSlice> slice_;
  std::array<int, 4> m_{1, 0, 0, 1};
  const int* perm_ = nullptr;
  int r2_ = -1;
};

/// The tables of one action set: slices built on first use, per direction and canonical heading.
class KinematicTables {
 public:
  /// cost_per_cell: s_c above (positive, <= cost / |d| for every move with d != 0);
  /// radius_cells: R (> 0), lowered if needed so that 2 s_c R fits the 16-bit entries.
  KinematicTables(std::vector<KinematicMove> moves, std::vector<double> heading_angles,
                  double cost_per_cell, int radius_cells);

  /// The tables of this action set and window, shared with every other caller that asks for
  /// the same (planners on other maps, incremental rebuilds): one build per process.
  static std::shared_ptr<KinematicTables> shared(const std::vector<KinematicMove>& moves,
                                                 const std::vector<double>& heading_angles,
                                                 double cost_per_cell, int radius_cells);

  enum class Direction {
    kToGoal,     ///< cost from (dx, dy, h) to the origin with the given heading
    kFromStart,  ///< cost from the origin with the given heading to (dx, dy, h)
  };
  /// The lookup for a goal heading (kToGoal; kAnyHeading: to any heading at the origin) or a
  /// start heading (kFromStart). Builds the slice if it is new; an invalid lookup if `stop`
  /// asked to stop first (nothing is kept then; a later call builds it). Thread-safe: callers
  /// asking for a slice being built wait for that build (or their own stop).
  /// `seconds`, if given, receives the time spent building or waiting (0 when it was ready).
  KinematicLookup lookup(Direction direction, int heading, const StopCondition* stop = nullptr,
                         double* seconds = nullptr) const;

  /// Builds every slice lookup() can ask for in `direction` (one per orbit of headings), in
  /// parallel threads (0: all hardware threads), so that no query waits for one. False if
  /// `stop` asked to stop first (the slices finished so far are kept).
  bool prepare(Direction direction, const StopCondition* stop = nullptr,
               unsigned threads = 0) const;

  int radius() const { return radius_; }
  int numHeadings() const { return headings_; }
  double costPerCell() const { return s_; }
  /// Symmetries found (1..8) and slices a full set of lookups needs per direction.
  int numSymmetries() const { return static_cast<int>(symmetries_.size()); }
  /// Bytes of the slices built so far, and the seconds their builds took.
  std::size_t bytes() const;
  double buildSeconds() const;
  /// Slices built so far.
  int slicesBuilt() const;

  /// Builds one slice outright (for tests): K for direction and canonical heading `heading`.
  std::shared_ptr<const KinematicSlice> buildSlice(Direction direction, int heading,
                                                   const StopCondition* stop) const;

 private:
  struct Symmetry {
    std::array<int, 4> m;   // (dx, dy) -> (m0 dx + m1 dy, m2 dx + m3 dy)
    std::vector<int> perm;  // heading -> heading
  };
  struct Entry;
  std::vector<KinematicMove> moves_;
  std::vector<double> angles_;
  double s_ = 0.0;
  int radius_ = 0, headings_ = 0;
  std::vector<Symmetry> symmetries_;  // [0] is the identity
  std::vector<int> identity_perm_;
  mutable std::mutex mutex_;
  mutable std::vector<std::shared_ptr<Entry>> entries_;  // per (direction, canonical heading)
  mutable double build_seconds_ = 0.0;
};

}  // namespace lattice
}  // namespace amha
