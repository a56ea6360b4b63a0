/// \file octree_fold.cpp
/// \brief OctreeAccel::fold(): the folded tree the simd traversals walk. Where a node's
/// children are themselves inner nodes that most rays entering the node also enter (a node
/// whose cells are all filled: a mesh's surface, a city's blocks), visiting them one after
/// the other costs a node test each; folding opens such children into their parent, so that
/// one 16-lane test (OctreeWideNode) decides the cells of two or more levels at once.
/// The cells, boxes, leaves and kept lists are the octree's own: only the way the traversal
/// reaches them changes (the kept groups of an opened node become slots of the wide node, each
/// a triangle list in its own box, as the plain traversal tests them: by entry distance), and
/// the answers stay the same bit for bit (tests/accel/test_octree_fold.cpp).
/// Folding works in place: a plain node that stays refers to a folded child with kWide; the
/// nodes opened into wide nodes stay where they are, for forEachNode and the other traversals.
#include "octree.h"
#include <algorithm>
#include <numeric>

namespace nori {

namespace {

/// A node becomes wide only when the cells it opens would have been entered, summed over
/// them, by at least this many of the rays that enter it (their surface areas relative to
/// the node's box, the usual estimate of the chance that a ray through one box enters
/// another, MacDonald & Booth 1990). A wide node's test costs about as much as a plain one
/// plus a third (16 lanes and an order lookup against 8 lanes), and every cell it opens
/// saves a node visit for the rays that enter it: below half a visit saved per entry the
/// extra lanes were measured to cost more than they save (nori-raytime with NORI_AB=fold:
/// with 0, the clutter scene's shadow rays lost what its primary rays gained).
constexpr float kWideGain = 0.5f;

/// Levels a wide node may span below its own: every level adds three bits to the order
/// keys (Slot::key), which must fit 64 bits.
constexpr int kMaxFoldLevels = 20;

float surfaceArea(const float lo[3], const float hi[3]) {
    const float x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
    return 2.0f * (x * y + y * z + z * x);
}

/// kOctants[code][signs]: the octant of a node with pattern code \p code for a ray with
/// direction signs \p signs (bit a: d[a] < 0); children in the order c ^ octant come front to
/// back (OctreeNode::Pattern).
struct OctantTable {
    uint8_t octant[64][8];
    OctantTable() {
        for (uint32_t code = 0; code < 64; ++code) {
            const OctreeNode::Pattern p = OctreeNode::Pattern::fromCode(code);
            for (unsigned signs = 0; signs < 8; ++signs) {
                uint32_t oct = 0;
                for (int l = 0; l < 3; ++l) oct |= ((signs >> (p.axis[l] & 3u)) & 1u) << (2 - l);
                octant[code][signs] = uint8_t(oct);
            }
        }
    }
};
const OctantTable kOctants;

/// One cell of a node being folded: a child of the node or of a node it opened.
struct Slot {
    uint32_t child, count;  ///< as in OctreeNode (count: the unfolded reference)
    float lo[3], hi[3];
    /// Per direction-sign combination, the cell's position front to back: the child indices
    /// xor the octants along its path from the folded node, three bits per level.
    uint64_t key[8];
    int levels;  ///< how many levels below the folded node the cell's parent lies
    bool kept;   ///< a kept group of an opened node (a list of triangles, like a leaf)

    bool openable() const { return (count & OctreeNode::kInner) && levels < kMaxFoldLevels; }
};

uint32_t patternOf(uint32_t ref) { return (ref >> OctreeNode::kPatternShift) & 63u; }

bool isEmpty(const OctreeNode &node, int c) { return node.count[c] == 0; }

int filledChildren(const OctreeNode &node) {
    int n = 0;
    for (int c = 0; c < 8; ++c) n += !isEmpty(node, c);
    return n;
}

/// The cells being folded into one node: at most sixteen (fold() checks before it opens one).
struct SlotList {
    Slot items[OctreeWideNode::kSlots];
    size_t n = 0;
    void erase(size_t i) {
        for (; i + 1 < n; ++i) items[i] = items[i + 1];
        --n;
    }
};

/// The kept groups of node \p index reached through \p ref (none without kKeptMask).
int keptGroups(const std::vector<OctreeKept> &kept, uint32_t index, uint32_t ref) {
    if (!(ref & OctreeNode::kKeptMask)) return 0;
    int n = 1;
    for (uint32_t g = index; kept[g].next; g = kept[g].next) ++n;
    return n;
}

/// The cells of node \p index of \p nodes (reached through \p ref) as slots one level below
/// \p parent's: its kept groups, each a list of triangles like a leaf, in front of all its
/// children (the order the plain traversal tests them in when their boxes come first), then
/// its filled children.
void appendChildren(const std::vector<OctreeNode> &nodes, const std::vector<OctreeKept> &kept, uint32_t index,
                    uint32_t ref, const Slot *parent, SlotList &out) {
    const OctreeNode &node = nodes[index];
    if (ref & OctreeNode::kKeptMask)
        for (uint32_t g = index;; g = kept[g].next) {
            Slot &s = out.items[out.n++];
            s.child = kept[g].offset;
            s.count = kept[g].count;
            for (int a = 0; a < 3; ++a) {
                s.lo[a] = kept[g].lo[a];
                s.hi[a] = kept[g].hi[a];
            }
            s.levels = parent ? parent->levels + 1 : 0;
            s.kept = true;
            for (unsigned signs = 0; signs < 8; ++signs) s.key[signs] = parent ? parent->key[signs] << 3 : 0u;
            if (!kept[g].next) break;
        }
    const uint8_t *octant = kOctants.octant[patternOf(ref)];
    for (int c = 0; c < 8; ++c) {
        if (isEmpty(node, c)) continue;
        Slot &s = out.items[out.n++];
        s.child = node.child[c];
        s.count = node.count[c];
        for (int a = 0; a < 3; ++a) {
            s.lo[a] = node.box[a][c];
            s.hi[a] = node.box[a][8 + c];
        }
        s.levels = parent ? parent->levels + 1 : 0;
        s.kept = false;
        for (unsigned signs = 0; signs < 8; ++signs)
            s.key[signs] = (parent ? parent->key[signs] << 3 : 0u) | (uint32_t(c) ^ octant[signs]);
    }
}

} // namespace

/// Folds the tree in place, depth first (a node before its subtree): plain nodes that stay
/// get kWide references to children that became wide nodes.
class OctreeFolder {
public:
    OctreeFolder(std::vector<OctreeNode> &nodes, const std::vector<OctreeKept> &kept, std::vector<OctreeWideNode> &wide,
                 std::vector<uint32_t> &source)
        : m_nodes(nodes), m_kept(kept), m_wide(wide), m_source(source) {}

    size_t opened = 0;  ///< nodes opened into wide nodes

    /// Fold the node \p index of m_nodes, reached through \p ref, and its subtree; returns the
    /// reference that now leads to it and sets \p child to its index (in m_wide if kWide).
    uint32_t fold(uint32_t index, uint32_t ref, uint32_t &child) {
        // Most nodes (those above leaves only) have no child to open: they stay plain at once.
        bool openable = false;
        for (int c = 0; c < 8; ++c) {
            const uint32_t r = m_nodes[index].count[c];
            openable |= bool(r & OctreeNode::kInner);
        }
        if (!openable) return keepPlain(index, ref, child);
        SlotList slots;
        appendChildren(m_nodes, m_kept, index, ref & ~OctreeNode::kKeptMask, nullptr, slots);  // (its own kept groups stay its own)

        // Open the largest cells first, while they fit in sixteen slots.
        float lo[3] = {Infinity, Infinity, Infinity}, hi[3] = {-Infinity, -Infinity, -Infinity};
        for (size_t i = 0; i < slots.n; ++i)
            for (int a = 0; a < 3; ++a) {
                const Slot &s = slots.items[i];
                lo[a] = std::min(lo[a], s.lo[a]);
                hi[a] = std::max(hi[a], s.hi[a]);
            }
        const float area = surfaceArea(lo, hi);
        float gain = 0.0f;
        size_t opens = 0;
        for (;;) {
            int best = -1;
            float bestArea = -1.0f;
            for (size_t i = 0; i < slots.n; ++i) {
                const Slot &s = slots.items[i];
                if (!s.openable()) continue;
                if (slots.n - 1 + size_t(filledChildren(m_nodes[s.child]) + keptGroups(m_kept, s.child, s.count)) >
                    size_t(OctreeWideNode::kSlots))
                    continue;
                const float a = surfaceArea(s.lo, s.hi);
                if (a > bestArea) {
                    bestArea = a;
                    best = int(i);
                }
            }
            if (best < 0) break;
            const Slot s = slots.items[size_t(best)];
            slots.erase(size_t(best));
            appendChildren(m_nodes, m_kept, s.child, s.count, &s, slots);
            gain += area > 0.0f ? bestArea / area : 1.0f;
            ++opens;
        }

        if (gain < kWideGain) return keepPlain(index, ref, child);
        opened += opens;
        child = uint32_t(m_wide.size());
        m_wide.emplace_back();
        m_source.push_back(index);
        writeWide(child, slots);
        // The cells' subtrees after the node itself (m_wide may move meanwhile: index, not reference).
        for (size_t i = 0; i < slots.n; ++i) {
            if (!(slots.items[i].count & OctreeNode::kInner)) continue;
            uint32_t sub;
            const uint32_t subRef = fold(slots.items[i].child, slots.items[i].count, sub);
            m_wide[child].child[i] = sub;
            m_wide[child].count[i] = subRef;
        }
        return ref | OctreeNode::kWide;
    }

private:
    /// Node \p index stays plain: only its inner children's references may change.
    uint32_t keepPlain(uint32_t index, uint32_t ref, uint32_t &child) {
        child = index;
        for (int c = 0; c < 8; ++c) {
            const uint32_t r = m_nodes[index].count[c];
            if (!(r & OctreeNode::kInner)) continue;
            uint32_t sub;
            const uint32_t subRef = fold(m_nodes[index].child[c], r, sub);
            m_nodes[index].child[c] = sub;
            m_nodes[index].count[c] = subRef;
        }
        return ref;
    }

    /// The wide node \p w's slots and orders (inner children's references are set by the caller).
    void writeWide(uint32_t w, const SlotList &list) {
        OctreeWideNode &node = m_wide[w];
        const Slot *slots = list.items;
        const int n = int(list.n);
        for (int s = 0; s < OctreeWideNode::kSlots; ++s) {
            const bool used = s < n;
            for (int a = 0; a < 3; ++a) {
                node.box[a][s] = used ? slots[size_t(s)].lo[a] : Infinity;
                node.box[a][OctreeWideNode::kSlots + s] = used ? slots[size_t(s)].hi[a] : -Infinity;
            }
            node.child[s] = used ? slots[size_t(s)].child : 0u;
            node.count[s] = used ? slots[size_t(s)].count | (slots[size_t(s)].kept ? kOctreeKeptTag : 0u) : 0u;
        }
        // Keys of cells at different levels are compared aligned to the deepest: no cell's path
        // is a prefix of another's (cells are the leaves of the opened subtree), so the first
        // three bits that differ decide, at the node where the two paths part.
        int deepest = 0;
        for (int s = 0; s < n; ++s) deepest = std::max(deepest, slots[s].levels);
        for (unsigned signs = 0; signs < 8; ++signs) {
            uint64_t key[OctreeWideNode::kSlots];
            for (int s = 0; s < OctreeWideNode::kSlots; ++s)
                key[s] = s < n ? slots[size_t(s)].key[signs] << (3 * (deepest - slots[size_t(s)].levels)) : ~uint64_t(0);
            uint8_t order[OctreeWideNode::kSlots];
            std::iota(order, order + OctreeWideNode::kSlots, uint8_t(0));
            // Back to front: the largest key (the farthest cell; unused slots before it) in lane 0.
            // A kept group shares its key with the front cell of its node: it comes just before it,
            // and a node's groups in their own order.
            std::sort(order, order + OctreeWideNode::kSlots, [&](uint8_t x, uint8_t y) {
                const bool keptX = x < n && slots[x].kept, keptY = y < n && slots[y].kept;
                return key[x] != key[y] ? key[x] > key[y] : keptX != keptY ? keptX < keptY : x > y;
            });
            std::copy(order, order + OctreeWideNode::kSlots, node.order[signs]);
        }
    }

    std::vector<OctreeNode> &m_nodes;
    const std::vector<OctreeKept> &m_kept;
    std::vector<OctreeWideNode> &m_wide;
    std::vector<uint32_t> &m_source;
};

void OctreeAccel::fold() {
    std::vector<OctreeWideNode>().swap(m_wide);
    std::vector<uint32_t>().swap(m_wideSource);
    m_rootChild = 0;
    if (!m_fold || m_traversal != Traversal::Simd || m_nodes.empty()) return;
    OctreeFolder folder(m_nodes, m_kept, m_wide, m_wideSource);
    m_rootCount = folder.fold(0, m_rootCount, m_rootChild);
    m_wide.shrink_to_fit();
    m_wideSource.shrink_to_fit();
    m_stats.wideNodes = m_wide.size();
    m_stats.openedNodes = folder.opened;
}

void OctreeAccel::forEachFoldedNode(const std::function<void(const FoldedView &)> &visit) const {
    if (m_nodes.empty()) return;
    std::vector<std::pair<uint32_t, uint32_t>> stack{{m_rootChild, m_rootCount}};
    while (!stack.empty()) {
        const auto [index, ref] = stack.back();
        stack.pop_back();
        FoldedView v{};
        v.wide = ref & OctreeNode::kWide;
        v.index = index;
        v.ref = ref;
        if (v.wide) {
            const OctreeWideNode &n = m_wide[index];
            v.source = m_wideSource[index];
            v.slots = OctreeWideNode::kSlots;
            v.child = n.child;
            v.count = n.count;
            v.wideNode = &n;
        } else {
            const OctreeNode &n = m_nodes[index];
            v.source = index;
            v.slots = 8;
            v.child = n.child;
            v.count = n.count;
        }
        visit(v);
        for (int s = v.slots - 1; s >= 0; --s)
            if (v.count[s] & OctreeNode::kInner) stack.push_back({v.child[s], v.count[s]});
    }
}

} // namespace nori
