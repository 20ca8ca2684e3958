#pragma once
// The discrete energy of eq. (34) as a list of named terms, each the energy at time (n + 1/2) k
// of the components and couplings that own it (Drum::energyTerms registers them; EnergyTerm.h),
// and the running totals of what the losses removed and the player put in or took out. With
// every loss off and the Newton snare solve, total() is constant to round-off between the
// player's actions (the quadratised solve's psi resets still remove a little, booked as
// dissipated); in every case balance() = total() + dissipated_J - injected_J is constant.
//
// Fixed capacity, no allocation: the drum fills it on the audio thread; copies are cheap.
// A term's column name (CSV, JSON) is its name and the unit: "batter_J".

#include <array>
#include <cassert>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>

namespace snaresim
{

class EnergyLedger
{
public:
    struct Term
    {
        std::string_view name; // a string literal, e.g. "batter"
        double value_J = 0.0;
    };

    static constexpr int capacity = 12;
    static constexpr std::string_view unit = "J";

    // A new term worth 0 J, at the end of the list; returns its index. name must outlive the
    // ledger (a string literal). Throws std::length_error beyond the capacity.
    int addTerm(std::string_view name)
    {
        if (count == capacity)
            throw std::length_error("EnergyLedger: more terms than its capacity");
        items[(size_t) count] = { name, 0.0 };
        return count++;
    }

    std::span<const Term> terms() const { return { items.data(), (size_t) count }; }
    int size() const { return count; }
    double operator[](int term) const
    {
        assert(term >= 0 && term < count);
        return items[(size_t) term].value_J;
    }
    // The value of the term called name; std::out_of_range when there is none.
    double value(std::string_view name) const
    {
        for (const auto& t : terms())
            if (t.name == name)
                return t.value_J;
        throw std::out_of_range("EnergyLedger: no term " + std::string(name));
    }
    // "batter" -> "batter_J": the term's CSV column and JSON key.
    static std::string columnName(std::string_view name)
    {
        std::string column(name);
        column += '_';
        column += unit;
        return column;
    }

    void set(int term, double value_J)
    {
        assert(term >= 0 && term < count);
        items[(size_t) term].value_J = value_J;
    }
    void change(int term, double delta_J)
    {
        assert(term >= 0 && term < count);
        items[(size_t) term].value_J += delta_J;
    }
    // Every value and both running totals back to 0; the terms stay registered.
    void clearValues()
    {
        for (auto& t : items)
            t.value_J = 0.0;
        dissipated_J = injected_J = 0.0;
    }

    double dissipated_J = 0.0; // cumulative sum of every term's step losses (eq. 34): the heads',
                               // the wires', the air's and the contacts' damping, and the
                               // quadratised snare solve's psi resets
    double injected_J = 0.0;   // net energy from the player: strikes, retrieved mallets, snares on/off

    // Sum of the terms, in their order (eq. 34).
    double total() const
    {
        if (count == 0)
            return 0.0;
        double sum = items[0].value_J;
        for (int i = 1; i < count; ++i)
            sum += items[(size_t) i].value_J;
        return sum;
    }
    double balance() const { return total() + dissipated_J - injected_J; }

private:
    std::array<Term, capacity> items {};
    int count = 0;
};

} // namespace snaresim
