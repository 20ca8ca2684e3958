#include "Presets.h"

#include "PresetFile.h"
#include "SnareSimPresetFiles.h" // Resources/Presets, embedded (juce_add_binary_data: plain data)

#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <string>
#include <vector>

namespace snaresim
{

namespace
{
struct FactoryPresets
{
    std::vector<PresetFile> files;
    std::vector<Preset> presets;
};

// The embedded files in the order of their file names ("01-...", "02-..."): the hosts' program
// numbers. Read once; a file that does not read is a build defect, so it stops the program.
const FactoryPresets& factory()
{
    static const FactoryPresets all = [] {
        std::vector<std::pair<std::string, std::string>> sources; // file name, text
        for (int i = 0; i < SnareSimPresetFiles::namedResourceListSize; ++i)
        {
            const char* resource = SnareSimPresetFiles::namedResourceList[i];
            int size = 0;
            const char* data = SnareSimPresetFiles::getNamedResource(resource, size);
            sources.emplace_back(SnareSimPresetFiles::getNamedResourceOriginalFilename(resource), std::string(data, (size_t) size));
        }
        std::sort(sources.begin(), sources.end());
        FactoryPresets f;
        f.files.reserve(sources.size());
        for (const auto& [file, text] : sources)
        {
            try
            {
                f.files.push_back(parsePresetFile(text));
            }
            catch (const PresetFileError& e)
            {
                throw std::logic_error("factory preset " + file + ": " + e.what());
            }
        }
        for (const auto& p : f.files)
            f.presets.push_back({ p.name, p.values });
        return f;
    }();
    return all;
}

bool equalNoCase(std::string_view a, std::string_view b)
{
    return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
               return std::tolower((unsigned char) x) == std::tolower((unsigned char) y);
           });
}
} // namespace

std::span<const Preset> factoryPresets() { return factory().presets; }

bool applyPreset(std::string_view name, ParameterSet& params)
{
    for (const auto& file : factory().files)
        if (equalNoCase(file.name, name))
        {
            params = parametersOf(file);
            return true;
        }
    return false;
}

} // namespace snaresim
