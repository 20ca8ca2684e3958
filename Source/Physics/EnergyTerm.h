#pragma once
// A term of the energy ledger and its owners. Every component (Membrane, SnareWires, Mallet,
// Cavity) and every coupling (MalletContact, SnareContact, CavityCoupling) has the same shape
// for the ledger:
//   double energy() const;    its stored energy at time (n + 1/2) k (0 when it stores none)
//   double stepLoss() const;  what its losses removed over the last step, k q^n (0 when lossless)
// An EnergyTerm names one term and lists its owners in order; a std::vector of components (the
// mallets) counts as the sum over its elements. All static: no virtual call, no allocation.
//
// Drum::energyTerms() holds the drum's list; record() fills the ledger from it each step.

#include "EnergyLedger.h"

#include <memory>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

namespace snaresim
{

template <class T>
concept EnergyOwner = requires(const T& owner)
{
    {
        owner.energy()
        } -> std::convertible_to<double>;
    {
        owner.stepLoss()
        } -> std::convertible_to<double>;
};

namespace detail
{
template <EnergyOwner T>
double energyOf(const T& owner)
{
    return owner.energy();
}
template <EnergyOwner T>
double stepLossOf(const T& owner)
{
    return owner.stepLoss();
}

template <EnergyOwner T>
double energyOf(const std::vector<T>& owners)
{
    double e = 0.0;
    for (const auto& o : owners)
        e += o.energy();
    return e;
}
template <EnergyOwner T>
double stepLossOf(const std::vector<T>& owners)
{
    double q = 0.0;
    for (const auto& o : owners)
        q += o.stepLoss();
    return q;
}
} // namespace detail

template <class... Owners>
class EnergyTerm
{
public:
    static_assert(sizeof...(Owners) > 0);

    EnergyTerm(std::string_view termName, const Owners&... owners) : name(termName), sources(owners...) {}

    // The same term, counted as exactly 0 J (energy and losses) while its owners are out of the
    // model (the snares thrown off).
    EnergyTerm when(bool inModel) const
    {
        EnergyTerm t = *this;
        t.on = inModel;
        return t;
    }

    // The same term left out of the ledger's layout (no column) when absent: for a component
    // only some drums have (the air box). An absent term must also be out of the model (0 J).
    EnergyTerm listedIf(bool present) const
    {
        EnergyTerm t = *this;
        t.listed = present;
        t.on = t.on && present;
        return t;
    }
    bool isListed() const { return listed; }

    // The owners' energies added in their order.
    double energy() const
    {
        if (! on)
            return 0.0;
        return std::apply(
            [](const auto& first, const auto&... rest) {
                double e = detail::energyOf(first);
                ((e += detail::energyOf(rest)), ...);
                return e;
            },
            sources);
    }

    double stepLoss() const
    {
        if (! on)
            return 0.0;
        return std::apply(
            [](const auto& first, const auto&... rest) {
                double q = detail::stepLossOf(first);
                ((q += detail::stepLossOf(rest)), ...);
                return q;
            },
            sources);
    }

    // True when owner is one of this term's owners.
    template <class T>
    bool owns(const T& owner) const
    {
        return std::apply([&](const auto&... o) { return (sameObject(o, owner) || ...); }, sources);
    }

    std::string_view name;

private:
    template <class A, class B>
    static bool sameObject(const A& a, const B& b)
    {
        if constexpr (std::is_same_v<A, B>)
            return std::addressof(a) == std::addressof(b);
        else
            return false;
    }

    std::tuple<const Owners&...> sources;
    bool on = true;
    bool listed = true;
};

// Register every listed term of the list in the ledger, in order.
template <class... Terms>
void registerTerms(EnergyLedger& ledger, const std::tuple<Terms...>& terms)
{
    std::apply([&](const auto&... t) { ((t.isListed() ? (void) ledger.addTerm(t.name) : (void) 0), ...); }, terms);
}

// The index of the first term owning owner (-1 when none does).
template <class... Terms, class T>
int termOwning(const std::tuple<Terms...>& terms, const T& owner)
{
    int index = -1, i = 0;
    std::apply(
        [&](const auto&... t) {
            ((index < 0 && t.isListed() && t.owns(owner) ? (void) (index = i) : (void) 0, i += t.isListed() ? 1 : 0), ...);
        },
        terms);
    return index;
}

// One step of bookkeeping: each term's energy at n + 1/2, and the sum of the terms' step losses
// (in the list's order) added to dissipated_J. The list must be the one registered.
template <class... Terms>
void record(EnergyLedger& ledger, const std::tuple<Terms...>& terms)
{
    static_assert(sizeof...(Terms) > 0);
    int i = 0;
    std::apply([&](const auto&... t) { ((t.isListed() ? ledger.set(i++, t.energy()) : (void) 0), ...); }, terms);
    const double loss = std::apply(
        [](const auto& first, const auto&... rest) {
            double q = first.stepLoss();
            ((q += rest.stepLoss()), ...);
            return q;
        },
        terms);
    ledger.dissipated_J += loss;
}

} // namespace snaresim
