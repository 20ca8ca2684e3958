#include "ParameterText.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <system_error>

namespace snaresim
{

namespace
{
std::string replaceAll(std::string s, std::string_view from, std::string_view to)
{
    for (auto at = s.find(from); at != std::string::npos; at = s.find(from, at + to.size()))
        s.replace(at, from.size(), to);
    return s;
}

std::string_view trimmed(std::string_view s)
{
    while (! s.empty() && std::isspace((unsigned char) s.front()))
        s.remove_prefix(1);
    while (! s.empty() && std::isspace((unsigned char) s.back()))
        s.remove_suffix(1);
    return s;
}

bool equalNoCase(std::string_view a, std::string_view b)
{
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower((unsigned char) x) == std::tolower((unsigned char) y);
           });
}

std::string capitalised(std::string_view s)
{
    std::string out(s);
    if (! out.empty())
        out.front() = (char) std::toupper((unsigned char) out.front());
    return out;
}

std::string fixed(double v, int decimals)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
    std::string text = buffer;
    // "-0", "-0.0": no sign on zero
    if (text.front() == '-' && text.find_first_not_of("-0.") == std::string::npos)
        text.erase(0, 1);
    return text;
}
} // namespace

std::string prettyUnit(std::string_view unit)
{
    return replaceAll(replaceAll(replaceAll(replaceAll(std::string(unit), "^alpha", "^\xce\xb1"), "^beta", "^\xce\xb2"), "^2", "\xc2\xb2"),
                      "^3", "\xc2\xb3");
}

ValueFormat valueFormat(const ParameterSpec& spec)
{
    ValueFormat f;
    f.schemaUnit = prettyUnit(spec.unit);
    f.unit = f.schemaUnit;
    const double largest = std::max(std::abs(spec.minValue), std::abs(spec.maxValue));

    // Small lengths and masses read better in µm, mm and g.
    if (spec.unit == "m" && largest <= 1.0e-3)
    {
        f.scale = 1.0e6;
        f.unit = "\xc2\xb5m"; // µm
    }
    else if (spec.unit == "m" && largest <= 0.5)
    {
        f.scale = 1000.0;
        f.unit = "mm";
    }
    else if (spec.unit == "kg" && largest <= 1.0)
    {
        f.scale = 1000.0;
        f.unit = "g";
    }
    else if (spec.unit == "Hz" && spec.minValue >= 1000.0) // and frequencies of kilohertz in kHz
    {
        f.scale = 1.0e-3;
        f.unit = "kHz";
    }

    if (spec.kind != ParamKind::continuous)
        return f;

    const bool manyDecades = spec.scale == ParamScale::logarithmic && spec.minValue > 0.0 && spec.maxValue / spec.minValue >= 1000.0;
    const double scaledLargest = largest * f.scale;
    if (manyDecades || (scaledLargest > 0.0 && scaledLargest < 0.1) || scaledLargest >= 1.0e6)
    {
        f.scientific = true;
        f.decimals = 1;
        return f;
    }
    const double span = (spec.maxValue - spec.minValue) * f.scale;
    f.decimals = span >= 100.0 ? 0 : span >= 10.0 ? 1 : span >= 0.5 ? 2 : 3;
    return f;
}

int numChoiceNames(const ParameterSpec& spec)
{
    if (spec.choices.empty())
        return 0;
    return 1 + (int) std::count(spec.choices.begin(), spec.choices.end(), '|');
}

std::string_view choiceName(const ParameterSpec& spec, int index)
{
    std::string_view rest = spec.choices;
    for (int i = 0; i < index && ! rest.empty(); ++i)
    {
        const auto bar = rest.find('|');
        rest = bar == std::string_view::npos ? std::string_view {} : rest.substr(bar + 1);
    }
    return rest.substr(0, rest.find('|'));
}

std::optional<int> choiceIndex(const ParameterSpec& spec, std::string_view name)
{
    for (int i = 0; i < numChoiceNames(spec); ++i)
        if (choiceName(spec, i) == name)
            return i;
    return std::nullopt;
}

std::string formatValue(const ParameterSpec& spec, double value)
{
    if (spec.kind == ParamKind::toggle || spec.kind == ParamKind::choice)
    {
        const int i = (int) std::lround(std::clamp(std::isfinite(value) ? value : spec.defaultValue, spec.minValue, spec.maxValue));
        return capitalised(choiceName(spec, i));
    }

    const auto f = valueFormat(spec);
    const double shown = value * f.scale;
    std::string number;
    if (f.scientific && shown != 0.0 && std::isfinite(shown))
    {
        int exponent = (int) std::floor(std::log10(std::abs(shown)));
        double mantissa = shown / std::pow(10.0, exponent);
        if (std::abs(std::round(mantissa * std::pow(10.0, f.decimals))) >= 10.0 * std::pow(10.0, f.decimals))
        {
            mantissa /= 10.0; // rounding carried the mantissa to 10
            ++exponent;
        }
        number = fixed(mantissa, f.decimals) + "e" + std::to_string(exponent);
    }
    else
        number = fixed(shown, f.decimals);
    return f.unit.empty() ? number : number + " " + f.unit;
}

std::optional<double> parseValue(const ParameterSpec& spec, std::string_view text, BareNumber bare)
{
    text = trimmed(text);
    if (spec.kind == ParamKind::toggle || spec.kind == ParamKind::choice)
        for (int i = 0; i < numChoiceNames(spec); ++i)
            if (equalNoCase(choiceName(spec, i), text))
                return (double) i;
    if (spec.kind == ParamKind::toggle)
        for (auto [name, v] : { std::pair { "yes", 1.0 }, { "true", 1.0 }, { "no", 0.0 }, { "false", 0.0 } })
            if (equalNoCase(name, text))
                return v;

    std::string_view digits = text;
    if (digits.size() > 1 && digits.front() == '+')
        digits.remove_prefix(1);
    double number = 0.0;
    const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), number);
    if (ec != std::errc {} || ! std::isfinite(number))
        return std::nullopt;

    const auto unit = trimmed(std::string_view(end, (std::size_t)(digits.data() + digits.size() - end)));
    const auto f = valueFormat(spec);
    if (unit.empty())
        return bare == BareNumber::writtenUnit ? number / f.scale : number;
    if (unit == f.unit)
        return number / f.scale;
    if (unit == f.schemaUnit || unit == spec.unit)
        return number;
    return std::nullopt;
}

std::optional<std::pair<ParamId, double>> readOldKey(std::string_view key, std::string_view text)
{
    if (! migrateOldKey(key, 0.0))
        return std::nullopt;
    text = trimmed(text);
    double number = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), number);
    if (text.empty() || ec != std::errc {} || end != text.data() + text.size() || ! std::isfinite(number))
        throw std::invalid_argument("'" + std::string(text) + "' is not a number");
    auto migrated = migrateOldKey(key, number);
    const auto& s = spec(migrated->first);
    migrated->second = std::clamp(migrated->second, s.minValue, s.maxValue);
    return migrated;
}

} // namespace snaresim
