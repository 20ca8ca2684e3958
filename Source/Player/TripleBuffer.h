#pragma once
// A lock-free triple buffer: one writer thread (the audio thread) publishes the newest value,
// one reader thread (the message thread) takes it. Neither ever waits or allocates; the writer
// always has a slot to write into and the reader always gets the newest complete value.
//
// The three objects are allocated once, in the constructor. Slots move between three roles:
// back (the writer's), middle (the last published, shared) and front (the reader's). The index
// of the middle slot and a "fresh" bit live in one atomic, swapped by each side.

#include <array>
#include <atomic>
#include <memory>

namespace snaresim
{

template <typename T>
class TripleBuffer
{
public:
    TripleBuffer()
    {
        for (auto& s : slots)
            s = std::make_unique<T>();
    }

    TripleBuffer(const TripleBuffer&) = delete;
    TripleBuffer& operator=(const TripleBuffer&) = delete;

    // Writer: the object to fill. Stays the writer's until publish().
    T& back() noexcept { return *slots[(size_t) backIndex]; }

    // Writer: make back() the newest value; the writer gets a free slot for the next one.
    void publish() noexcept
    {
        const int previousMiddle = middle.exchange(backIndex | freshBit, std::memory_order_acq_rel);
        backIndex = previousMiddle & indexMask;
    }

    // Reader: true when a value was published since the last take; then front() holds it.
    bool take() noexcept
    {
        if ((middle.load(std::memory_order_acquire) & freshBit) == 0)
            return false;

        const int previousMiddle = middle.exchange(frontIndex, std::memory_order_acq_rel);
        frontIndex = previousMiddle & indexMask;
        return true;
    }

    // Reader: the value taken last.
    const T& front() const noexcept { return *slots[(size_t) frontIndex]; }

private:
    static constexpr int indexMask = 3;
    static constexpr int freshBit = 4;

    std::array<std::unique_ptr<T>, 3> slots;
    int backIndex = 0;             // writer only
    int frontIndex = 1;            // reader only
    std::atomic<int> middle { 2 }; // shared: index | freshBit
};

} // namespace snaresim
