#include "PresetFileActions.h"

#include "PluginProcessor.h"
#include "PresetFile.h"

namespace snaresim::ui
{

juce::String loadPresetFile (SnareSimAudioProcessor& processor, const juce::File& file)
{
    const auto where = file.getFileName() + ": ";
    if (! file.existsAsFile())
        return where + "no such file";
    if (file.getSize() > 64 * 1024)
        return where + "not a preset file: larger than 64 KiB";
    juce::MemoryBlock data;
    if (! file.loadFileAsData (data))
        return where + "cannot read it";
    try
    {
        const auto preset = parsePresetFile (std::string_view (static_cast<const char*> (data.getData()), data.getSize()));
        processor.applyParameters (parametersOf (preset));
    }
    catch (const PresetFileError& e)
    {
        return where + e.what();
    }
    return {};
}

juce::String savePresetFile (const SnareSimAudioProcessor& processor, const juce::File& file)
{
    const auto text = formatPresetFile (file.getFileNameWithoutExtension().toStdString(), processor.parameterValues());
    // replaceWithText writes a temporary file beside it, then moves it over the old one
    if (! file.replaceWithText (juce::String::fromUTF8 (text.data(), (int) text.size()), false, false, "\n"))
        return file.getFileName() + ": cannot write it";
    return {};
}

} // namespace snaresim::ui
