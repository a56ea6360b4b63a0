/// \file stack_arena.h
/// \brief StackArena: per-thread last-in-first-out memory for the octree build's per-node
/// scratch lists and children's reference lists (octree_build.cpp).
#pragma once

#include "huge_pages.h"
#include <algorithm>
#include <cstddef>
#include <vector>

// Under AddressSanitizer the arena poisons what it has not handed out, so that an overrun of
// one list into the next (or a use after release) is reported as it would be with malloc.
#if defined(__SANITIZE_ADDRESS__)
#define NORI_ARENA_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define NORI_ARENA_ASAN 1
#endif
#endif
#ifdef NORI_ARENA_ASAN
#include <sanitizer/asan_interface.h>
#define NORI_ARENA_POISON(p, n) ASAN_POISON_MEMORY_REGION(p, n)
#define NORI_ARENA_UNPOISON(p, n) ASAN_UNPOISON_MEMORY_REGION(p, n)
#else
#define NORI_ARENA_POISON(p, n) ((void)(p), (void)(n))
#define NORI_ARENA_UNPOISON(p, n) ((void)(p), (void)(n))
#endif

namespace nori::octree_build {

/// \brief Memory handed out like a stack: allocate(), and release() back to an earlier mark().
/// split() takes its scratch and its children's lists here and gives them back when it returns;
/// every node below it (built in its turn, or as a task this thread runs while it waits)
/// takes and returns its own above them first, so the order is always last in, first out.
/// A malloc and a free per list, and the page faults of blocks that glibc returned to the
/// system and mapped again, were about 7 % of a 100k-triangle build's thread time.
///
/// One arena per thread (local()). Its blocks stay between the nodes of a build; when the
/// outermost user releases everything, all but the first few MiB are freed (trim()).
class StackArena {
public:
    struct Mark {
        size_t block, used;
    };
    static StackArena &local() {
        thread_local StackArena arena;
        return arena;
    }
    StackArena() = default;
    StackArena(const StackArena &) = delete;
    StackArena &operator=(const StackArena &) = delete;
    ~StackArena() { freeFrom(0); }

    Mark mark() const { return {m_block, m_used}; }
    /// \brief \p n uninitialised elements of a trivial type, aligned as malloc aligns (16 bytes
    /// on x86-64; each list starts a multiple of 64 bytes from its block's start).
    template <typename T> T *allocate(size_t n) { return static_cast<T *>(allocateBytes(n * sizeof(T))); }
    /// \brief Give back everything allocated since \p m.
    void release(Mark m) {
        // (Everything from the mark on: the rest of its block and every later block.)
        for (size_t b = m.block; b < m_blocks.size() && b <= m_block; ++b) {
            const size_t from = b == m.block ? m.used : 0;
            NORI_ARENA_POISON(m_blocks[b].data + from, m_blocks[b].size - from);
        }
        m_block = m.block;
        m_used = m.used;
        if (m_block == 0 && m_used == 0) trim();
    }

private:
    struct Block {
        char *data;
        size_t size;
    };
    static constexpr size_t kMinBlock = size_t(1) << 20;
    static constexpr size_t kRetain = size_t(4) << 20;

    void *allocateBytes(size_t requested) {
        const size_t bytes = (requested + 63) & ~size_t(63);
        if (m_block < m_blocks.size() && m_blocks[m_block].size - m_used >= bytes) {
            void *p = m_blocks[m_block].data + m_used;
            m_used += bytes;
            NORI_ARENA_UNPOISON(p, requested);
            return p;
        }
        // The next block (left from earlier in the build) if it is large enough; else the
        // blocks from there on are replaced by one that is.
        const size_t next = m_blocks.empty() ? 0 : m_block + 1;
        if (next >= m_blocks.size() || m_blocks[next].size < bytes) {
            freeFrom(next);
            const size_t size = std::max(2 * bytes, kMinBlock);
            m_blocks.push_back({static_cast<char *>(allocateLarge(size)), size});
            NORI_ARENA_POISON(m_blocks.back().data, size);
        }
        m_block = next;
        m_used = bytes;
        NORI_ARENA_UNPOISON(m_blocks[next].data, requested);
        return m_blocks[next].data;
    }
    /// Once everything is released: the first blocks, up to kRetain bytes, are kept for the
    /// next build on this thread, the others freed. (Freeing all made repeated builds of
    /// small scenes fault the same pages in again every time: the 25k-triangle tabletop's build
    /// took 4.5-4.8 ms instead of 3.5-3.7 ms with malloc; a bounded amount, as malloc itself
    /// keeps freed memory up to a threshold, not the largest scene's lists for good.)
    void trim() {
        size_t keep = 0, bytes = 0;
        while (keep < m_blocks.size() && bytes + m_blocks[keep].size <= kRetain) bytes += m_blocks[keep++].size;
        freeFrom(keep);
    }
    void freeFrom(size_t b) {
        for (size_t k = b; k < m_blocks.size(); ++k) {
            NORI_ARENA_UNPOISON(m_blocks[k].data, m_blocks[k].size);  // (the allocator may reuse it)
            releaseLarge(m_blocks[k].data);
        }
        m_blocks.resize(std::min(b, m_blocks.size()));
    }

    std::vector<Block> m_blocks;
    size_t m_block = 0, m_used = 0;  ///< the block in use and the bytes taken of it
};

} // namespace nori::octree_build
