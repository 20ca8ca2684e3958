#include "PresetFileActions.h"

#include "PluginProcessor.h"
#include "PresetFile.h"

#include <filesystem>

namespace snaresim::ui
{

juce::String loadPresetFile(SnareSimAudioProcessor& processor, const juce::File& file)
{
    try
    {
        processor.applyParameters(parametersOf(readPresetFile(std::filesystem::path(file.getFullPathName().toStdString()))));
    }
    catch (const PresetFileError& e)
    {
        return file.getFileName() + ": " + e.what();
    }
    return {};
}

juce::String savePresetFile(const SnareSimAudioProcessor& processor, const juce::File& file)
{
    const auto text = formatPresetFile(file.getFileNameWithoutExtension().toStdString(), processor.parameterValues());
    // replaceWithText writes a temporary file beside it, then moves it over the old one
    if (! file.replaceWithText(juce::String::fromUTF8(text.data(), (int) text.size()), false, false, "\n"))
        return file.getFileName() + ": cannot write it";
    return {};
}

} // namespace snaresim::ui
