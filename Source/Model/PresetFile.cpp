#include "PresetFile.h"

#include "ParameterText.h"

#include <array>
#include <charconv>
#include <fstream>
#include <optional>
#include <stdexcept>

namespace snaresim
{

namespace
{
constexpr std::size_t kMaxPresetBytes = 64 * 1024;

std::string_view trimmed(std::string_view s)
{
    while (! s.empty() && (s.front() == ' ' || s.front() == '\t'))
        s.remove_prefix(1);
    while (! s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

[[noreturn]] void fail(int line, const std::string& what) { throw PresetFileError("line " + std::to_string(line) + ": " + what); }

std::string quoted(std::string_view s)
{
    std::string q(1, '\'');
    q.append(s);
    q.push_back('\'');
    return q;
}

std::string shortest(double v)
{
    std::array<char, 32> b {};
    const auto [end, ec] = std::to_chars(b.data(), b.data() + b.size(), v);
    return ec == std::errc {} ? std::string(b.data(), end) : std::to_string(v);
}
} // namespace

PresetFile parsePresetFile(std::string_view text)
{
    if (text.size() > kMaxPresetBytes)
        throw PresetFileError("not a preset file: larger than 64 KiB");
    if (text.find('\0') != std::string_view::npos)
        throw PresetFileError("not a preset file: it holds binary data");
    if (text.substr(0, 3) == "\xEF\xBB\xBF") // a UTF-8 byte order mark
        text.remove_prefix(3);

    PresetFile preset;
    bool named = false;
    std::array<bool, kNumParameters> seen {};
    ParameterSet check;
    int lineNo = 0;
    while (! text.empty())
    {
        ++lineNo;
        const auto eol = text.find('\n');
        std::string_view line = text.substr(0, eol);
        text.remove_prefix(eol == std::string_view::npos ? text.size() : eol + 1);
        if (const auto hash = line.find('#'); hash != std::string_view::npos)
            line = line.substr(0, hash);
        line = trimmed(line);
        if (line.empty())
            continue;
        const auto eq = line.find('=');
        if (eq == std::string_view::npos)
            fail(lineNo, quoted(line) + " is not KEY = VALUE");
        const auto key = trimmed(line.substr(0, eq));
        const auto value = trimmed(line.substr(eq + 1));
        if (key == "name")
        {
            if (named)
                fail(lineNo, "the name is given twice");
            if (value.empty())
                fail(lineNo, "the name is empty");
            preset.name = std::string(value);
            named = true;
            continue;
        }
        // Today's key, or an older schema's, its value migrated (a preset of then is still its drum).
        auto id = findParameter(key);
        std::optional<double> v;
        if (id)
            v = parseValue(spec(*id), value, BareNumber::schemaUnit);
        else
        {
            std::optional<std::pair<ParamId, double>> old;
            try
            {
                old = readOldKey(key, value);
            }
            catch (const std::invalid_argument&)
            {
                fail(lineNo, quoted(key) + ": cannot read the value " + quoted(value));
            }
            if (! old)
                fail(lineNo, "unknown parameter " + quoted(key) + " (see snaresim-render --list-params)");
            id = old->first;
            v = old->second;
        }
        if (seen[(std::size_t) *id])
            fail(lineNo, "parameter " + quoted(key) + " is given twice");
        seen[(std::size_t) *id] = true;
        if (! v)
            fail(lineNo, quoted(key) + ": cannot read the value " + quoted(value));
        try
        {
            check.set(*id, *v);
        }
        catch (const std::out_of_range& e)
        {
            fail(lineNo, e.what());
        }
        preset.values.emplace_back(*id, *v);
    }
    if (! named)
        throw PresetFileError("not a preset file: no 'name = ...' line");
    return preset;
}

PresetFile readPresetFile(const std::filesystem::path& path)
{
    std::error_code ec;
    if (! std::filesystem::is_regular_file(path, ec))
        throw PresetFileError("no such preset file");
    const auto size = std::filesystem::file_size(path, ec);
    if (ec)
        throw PresetFileError("cannot read it");
    if (size > kMaxPresetBytes)
        throw PresetFileError("not a preset file: larger than 64 KiB");
    std::ifstream in(path, std::ios::binary);
    std::string text((std::size_t) size, '\0');
    if (! in || ! in.read(text.data(), (std::streamsize) size))
        throw PresetFileError("cannot read it");
    return parsePresetFile(text);
}

ParameterSet parametersOf(const PresetFile& preset)
{
    ParameterSet params;
    for (const auto& [id, value] : preset.values)
        params.set(id, value);
    return params;
}

std::string formatPresetFile(std::string_view name, const ParameterSet& params)
{
    std::string oneLine(name);
    for (char& c : oneLine)
        if (c == '\n' || c == '\r' || c == '#')
            c = ' ';
    const auto title = trimmed(oneLine);
    std::string out = "# SnareSim preset (snaresim-render --list-params lists the parameters)\nname = " +
                      std::string(title.empty() ? "Untitled" : title) + "\n";
    for (const auto& s : parameterSpecs())
    {
        const double v = params.get(s.id);
        if (v == s.defaultValue)
            continue;
        out.append(s.key);
        out.append(" = ");
        if (s.kind == ParamKind::toggle || s.kind == ParamKind::choice)
            out.append(choiceName(s, (int) v));
        else
        {
            out += shortest(v);
            if (! s.unit.empty() && s.kind == ParamKind::continuous)
            {
                out.push_back(' ');
                out.append(s.unit);
            }
        }
        out += "\n";
    }
    return out;
}

} // namespace snaresim
