#include "cut/grid_max_flow.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cstdint>
#include <cstring>
#include <vector>

namespace movseg {
namespace {

// Directions to a neighbour; d ^ 1 is the opposite one.
enum Direction : std::int8_t { kRight = 0, kLeft = 1, kDown = 2, kUp = 3 };
// A node's parent: one of the directions, or one of these.
constexpr std::int8_t kTerminal = 4, kOrphan = 5, kNone = 6;
enum Tree : std::uint8_t { kSourceTree = 0, kSinkTree = 1 };
constexpr int kEnd = -1, kIdle = -2;  // Node::next: last in the active queue; not in it

}  // namespace

struct GridMaxFlow::Node {
  std::array<float, 4> cap{};  // residual capacity to the neighbour in each direction
  float terminal = 0;          // > 0: residual from the source; < 0: to the sink
  int ts = 0, dist = 0;        // when the distance to the tree's root was last worked out, and
                               // that distance (the root counts 1)
  int next = kIdle;            // the active queue
  std::int8_t parent = kNone;
  std::uint8_t tree = kSourceTree;
};

namespace {

using Node = GridMaxFlow::Node;

// Calls visit(x, y) for each kFree pixel of `state`, in raster order. memchr skips each run of
// fixed pixels, most of a banded grid.
template <typename Visit>
void forEachFreePixel(const cv::Mat& state, Visit visit) {
  const int width = state.cols;
  for (int y = 0; y < state.rows; ++y) {
    const uchar* s = state.ptr<uchar>(y);
    for (int x = 0; x < width; ++x) {
      if (s[x] != kFree) {
        const void* next_free = std::memchr(s + x, kFree, static_cast<size_t>(width - x));
        if (next_free == nullptr) break;
        x = static_cast<int>(static_cast<const uchar*>(next_free) - s);
      }
      visit(x, y);
    }
  }
}

// The max-flow of one energy, on nodes and orphans that a GridMaxFlow keeps: built, run()
// once, then read by onSourceSide(). The grid is padded by one node on every side (parent
// kNone, no capacity), so that every node of the image has four neighbours to look at.
class GridFlow {
 public:
  GridFlow(const GridEnergy& energy, const cv::Mat& state, std::vector<Node>* nodes,
           std::vector<int>* orphans)
      : width_(state.cols + 2),
        nodes_(*nodes),
        orphans_(*orphans),
        offset_{1, -1, state.cols + 2, -(state.cols + 2)} {
    nodes_.assign(static_cast<size_t>(state.cols + 2) * static_cast<size_t>(state.rows + 2), Node());
    orphans_.clear();
    forEachFreePixel(state, [&](int x, int y) { setCapacities(energy, state, x, y); });
  }

  void run() {
    for (;;) {
      int from = -1;
      const int direction = grow(&from);
      if (from < 0) return;
      augment(from, direction);
      adoptOrphans();
    }
  }

  // GCGraph's reading: a node is foreground unless it last belonged to the sink's tree.
  bool onSourceSide(int x, int y) const { return node(index(x, y)).tree == kSourceTree; }

  int index(int x, int y) const { return (y + 1) * width_ + x + 1; }

 private:
  Node& node(int i) { return nodes_[static_cast<size_t>(i)]; }
  const Node& node(int i) const { return nodes_[static_cast<size_t>(i)]; }

  // The free pixel (x, y): its terminal capacity (cost_bg from the source, cost_fg to the sink,
  // less what both share; an edge to a fixed pixel adds to it) and its edges to free pixels.
  // The terminal sums its terms in raster order of the edges (up, left, own, right, down), the
  // order a sweep over all edges would add them in. A node with a terminal capacity is active,
  // the queue in raster order.
  void setCapacities(const GridEnergy& energy, const cv::Mat& state, int x, int y) {
    const int i = index(x, y);
    Node& n = node(i);
    const float* right = energy.right.ptr<float>(y);
    const float* down = energy.down.ptr<float>(y);
    const uchar* s = state.ptr<uchar>(y);
    if (y > 0) link(state.ptr<uchar>(y - 1)[x], energy.down.ptr<float>(y - 1)[x], kUp, &n);
    if (x > 0) link(s[x - 1], right[x - 1], kLeft, &n);
    n.terminal += energy.cost_bg.ptr<float>(y)[x] - energy.cost_fg.ptr<float>(y)[x];
    if (x + 1 < state.cols) link(s[x + 1], right[x], kRight, &n);
    if (y + 1 < state.rows) link(state.ptr<uchar>(y + 1)[x], down[x], kDown, &n);
    if (n.terminal == 0) return;
    n.parent = kTerminal;
    n.tree = n.terminal < 0 ? kSinkTree : kSourceTree;
    n.dist = 1;
    enqueue(i);
  }

  // The edge of weight `weight` from a free node to its neighbour in direction d (state sb).
  static void link(uchar sb, float weight, Direction d, Node* a) {
    if (sb == kFree) {
      a->cap[static_cast<size_t>(d)] = weight;
    } else {
      a->terminal += sb == kFixedForeground ? weight : -weight;
    }
  }

  void enqueue(int i) {
    if (node(i).next != kIdle) return;
    node(i).next = kEnd;
    if (last_ == kEnd) {
      first_ = i;
    } else {
      node(last_).next = i;
    }
    last_ = i;
  }

  void dequeueFirst() {
    const int i = first_;
    first_ = node(i).next;
    node(i).next = kIdle;
    if (first_ == kEnd) last_ = kEnd;
  }

  // The residual capacity a tree grows along from `from` to its neighbour in `direction`: from
  // -> neighbour in the source's tree (flow leaves the source), neighbour -> from in the sink's
  // (flow goes to the sink).
  float treeResidual(std::uint8_t tree, int from, int direction) const {
    const int to = from + offset_[direction];
    return tree == kSourceTree ? node(from).cap[static_cast<size_t>(direction)]
                               : node(to).cap[static_cast<size_t>(direction ^ 1)];
  }

  // Grows both trees from the active nodes until one touches the other: returns the direction
  // from *from (left at the head of the queue, still active) to the node of the other tree.
  int grow(int* from) {
    while (first_ != kEnd) {
      const int v = first_;
      const Node& nv = node(v);
      if (nv.parent != kNone) {
        // v's own fields do not change in the loop: in locals, not read again after each store.
        const std::uint8_t tree = nv.tree;
        const int ts = nv.ts, dist = nv.dist + 1;
        for (int d = 0; d < 4; ++d) {
          if (treeResidual(tree, v, d) == 0) continue;
          Node& nu = node(v + offset_[d]);
          if (nu.parent == kNone) {
            nu.tree = tree;
            nu.parent = static_cast<std::int8_t>(d ^ 1);
            nu.ts = ts;
            nu.dist = dist;
            enqueue(v + offset_[d]);
          } else if (nu.tree != tree) {
            *from = v;
            return d;
          } else if (nu.dist > dist && nu.ts <= ts) {  // a shorter way to the root
            nu.parent = static_cast<std::int8_t>(d ^ 1);
            nu.ts = ts;
            nu.dist = dist;
          }
        }
      }
      dequeueFirst();
    }
    return -1;
  }

  // The bottleneck of the path source -> ... -> s -> t -> ... -> sink, s in the source tree.
  float bottleneck(int s, int t, int direction) const {
    float least = node(s).cap[static_cast<size_t>(direction)];
    int x = s;
    for (int p = node(x).parent; p < kTerminal; p = node(x).parent) {
      const int up = x + offset_[p];
      least = std::min(least, node(up).cap[static_cast<size_t>(p ^ 1)]);
      x = up;
    }
    least = std::min(least, node(x).terminal);
    x = t;
    for (int p = node(x).parent; p < kTerminal; p = node(x).parent) {
      least = std::min(least, node(x).cap[static_cast<size_t>(p)]);
      x += offset_[p];
    }
    return std::min(least, -node(x).terminal);
  }

  void makeOrphan(int i) {
    node(i).parent = kOrphan;
    orphans_.push_back(i);
  }

  // Pushes the bottleneck along the path; nodes whose link to their parent (or terminal)
  // saturates become orphans.
  void augment(int from, int direction) {
    int s = from, t = from + offset_[direction];
    if (node(from).tree == kSinkTree) {
      std::swap(s, t);
      direction ^= 1;
    }
    const float flow = bottleneck(s, t, direction);
    // Every capacity on the path is positive, unless one is NaN: then nothing would saturate
    // and the same path would be found for ever. Stop, as GCGraph does.
    CV_Assert(flow > 0);
    node(s).cap[static_cast<size_t>(direction)] -= flow;
    node(t).cap[static_cast<size_t>(direction ^ 1)] += flow;
    int x = s;
    for (int p = node(x).parent; p < kTerminal; p = node(x).parent) {
      const int up = x + offset_[p];
      node(x).cap[static_cast<size_t>(p)] += flow;
      if ((node(up).cap[static_cast<size_t>(p ^ 1)] -= flow) == 0) makeOrphan(x);
      x = up;
    }
    if ((node(x).terminal -= flow) == 0) makeOrphan(x);
    x = t;
    for (int p = node(x).parent; p < kTerminal; p = node(x).parent) {
      const int up = x + offset_[p];
      node(up).cap[static_cast<size_t>(p ^ 1)] += flow;
      if ((node(x).cap[static_cast<size_t>(p)] -= flow) == 0) makeOrphan(x);
      x = up;
    }
    if ((node(x).terminal += flow) == 0) makeOrphan(x);
  }

  // The distance from i to its tree's root through valid parents (the root counts 1; INT_MAX
  // when the way ends at an orphan), written on the nodes of the way with the current time so
  // that the next orphan's search stops there.
  int distanceToRoot(int i) {
    int dist = 0;
    for (int x = i;;) {
      Node& n = node(x);
      if (n.ts == time_) {
        dist += n.dist;
        break;
      }
      ++dist;
      if (n.parent == kTerminal) {
        n.ts = time_;
        n.dist = 1;
        break;
      }
      if (n.parent > kTerminal) return INT_MAX;  // an orphan (a free node cannot be on the way)
      x += offset_[n.parent];
    }
    int remaining = dist;
    for (int x = i; node(x).ts != time_; x += offset_[node(x).parent]) {
      node(x).ts = time_;
      node(x).dist = remaining--;
    }
    return dist;
  }

  void adoptOrphans() {
    ++time_;
    while (!orphans_.empty()) {
      const int o = orphans_.back();
      orphans_.pop_back();
      const std::uint8_t tree = node(o).tree;
      int best = -1, best_dist = INT_MAX;
      for (int d = 0; d < 4; ++d) {
        const int u = o + offset_[d];
        if (!canParent(tree, o, d)) continue;
        const int dist = distanceToRoot(u);
        if (dist < INT_MAX && dist + 1 < best_dist) {
          best_dist = dist + 1;
          best = d;
        }
      }
      if (best >= 0) {
        node(o).parent = static_cast<std::int8_t>(best);
        node(o).ts = time_;
        node(o).dist = best_dist;
        continue;
      }
      freeOrphan(o, tree);
    }
  }

  // Whether the neighbour of o in direction d belongs to o's tree and can feed it.
  bool canParent(std::uint8_t tree, int o, int d) const {
    const Node& nu = node(o + offset_[d]);
    return nu.tree == tree && nu.parent != kNone && treeResidual(tree, o + offset_[d], d ^ 1) != 0;
  }

  // No parent: o leaves its tree; its neighbours in the tree that could feed it become active
  // again, and those whose parent it was become orphans.
  void freeOrphan(int o, std::uint8_t tree) {
    node(o).ts = 0;
    for (int d = 0; d < 4; ++d) {
      const int u = o + offset_[d];
      Node& nu = node(u);
      if (nu.tree != tree || nu.parent == kNone) continue;
      if (treeResidual(tree, u, d ^ 1) != 0) enqueue(u);
      if (nu.parent == (d ^ 1)) makeOrphan(u);
    }
    node(o).parent = kNone;
  }

  int width_;
  std::vector<Node>& nodes_;
  std::vector<int>& orphans_;
  std::array<int, 4> offset_;
  int first_ = kEnd, last_ = kEnd;
  int time_ = 0;
};

}  // namespace

GridMaxFlow::GridMaxFlow() = default;
GridMaxFlow::~GridMaxFlow() = default;

void GridMaxFlow::label(const GridEnergy& energy, const cv::Mat& state, int* nodes,
                        cv::Mat* labels) {
  GridFlow flow(energy, state, &nodes_, &orphans_);
  flow.run();
  labels->create(state.size(), CV_8U);
  const int width = state.cols;  // a local, which the byte stores cannot change: GCC vectorises
  for (int y = 0; y < state.rows; ++y) {  // the fixed pixels' labels
    const uchar* s = state.ptr<uchar>(y);
    uchar* out = labels->ptr<uchar>(y);
    for (int x = 0; x < width; ++x) out[x] = s[x] == kFixedForeground ? 255 : 0;
  }
  *nodes = 0;
  forEachFreePixel(state, [&](int x, int y) {
    ++*nodes;
    labels->at<uchar>(y, x) = flow.onSourceSide(x, y) ? 255 : 0;
  });
}

}  // namespace movseg
