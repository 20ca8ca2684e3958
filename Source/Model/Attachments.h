#pragma once
// A list of a drum's parts of one kind (AttachedAir.h, HeadContact.h), each built from the
// drum's config and its heads (the arguments the list is built with), constructed, stepped and
// listed in the ledger in the order given: each(f) calls f on every one in that order,
// energyTerms() is their EnergyTerms in that order, get<A>() the one of type A.

#include <tuple>
#include <type_traits>

namespace snaresim
{

template <class... Parts>
class Attachments;

template <>
class Attachments<>
{
public:
    template <class... Args>
    explicit Attachments(Args&...)
    {}
    template <class F>
    void each(F&&)
    {}
    template <class F>
    void each(F&&) const
    {}
    auto energyTerms() const { return std::tuple {}; }
};

template <class First, class... Rest>
class Attachments<First, Rest...>
{
public:
    template <class... Args>
    explicit Attachments(Args&... args) : first(args...), rest(args...)
    {}

    template <class F>
    void each(F&& f)
    {
        f(first);
        rest.each(f);
    }
    template <class F>
    void each(F&& f) const
    {
        f(first);
        rest.each(f);
    }

    template <class A>
    const A& get() const
    {
        if constexpr (std::is_same_v<A, First>)
            return first;
        else
            return rest.template get<A>();
    }
    template <class A>
    A& get()
    {
        if constexpr (std::is_same_v<A, First>)
            return first;
        else
            return rest.template get<A>();
    }

    auto energyTerms() const { return std::tuple_cat(std::tuple { first.energyTerm() }, rest.energyTerms()); }

private:
    First first;
    Attachments<Rest...> rest;
};

} // namespace snaresim
