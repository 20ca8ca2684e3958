#pragma once
// The live picture of the drum: the batter and carry heads as two discs, displacement as colour
// (diverging map: blue down, white at rest, red up) scaled by a slowly decaying maximum of the
// snapshot's peak displacement, and the snare wires over the carry head, each drawn from its
// displacement samples and highlighted where it presses on the head.
//
// update() is called from the editor's timer with a new snapshot; it re-renders the two head
// images (juce::Image::BitmapData, no per-pixel drawing calls). paint() only blits them and
// strokes two paths for the wires. No allocation after the first frame at a given size.

#include "DrumSnapshot.h"
#include "EditorLookAndFeel.h"

#include <juce_gui_basics/juce_gui_basics.h>

#include <array>

namespace snaresim::ui
{

class DrumView final : public juce::Component
{
public:
    explicit DrumView(EditorLookAndFeel&);

    // A new snapshot (message thread).
    void update(const DrumSnapshot&);

    // The current colour scale: displacement shown at full colour (m).
    float getColourScale() const noexcept { return headScale; }

    // A line over the picture (empty: none), e.g. that the air box does not keep up here.
    void setNotice(const juce::String& text);
    const juce::String& getNotice() const noexcept { return notice; }

    // True once a snapshot has been shown.
    bool hasShownSnapshot() const noexcept { return hasSnapshot; }

    // Where the two heads are drawn (in this component's coordinates; for tests).
    juce::Rectangle<float> getBatterDisc() const noexcept { return batterDisc; }
    juce::Rectangle<float> getCarryDisc() const noexcept { return carryDisc; }

    void paint(juce::Graphics&) override;
    void resized() override;

    // The diverging colour map, t in [-1, 1] (exposed for the legend and tests).
    static juce::Colour colourFor(float t);

private:
    void renderHeads();
    void renderHead(const std::array<float, DrumSnapshot::raster * DrumSnapshot::raster>& raster, juce::Image& image) const;
    void paintHead(juce::Graphics&, juce::Rectangle<float> disc, const juce::Image&) const;
    void paintWires(juce::Graphics&, juce::Rectangle<float> disc);
    void paintLegend(juce::Graphics&, juce::Rectangle<int> area) const;

    EditorLookAndFeel& look;

    DrumSnapshot shown;
    bool hasSnapshot = false;
    juce::String notice;

    // Slowly decaying maxima: the colour scale of the heads and the drawing scale of the wires.
    float headScale = 0.0f;
    float wireScale = 0.0f;

    std::array<juce::PixelARGB, 512> lut {};
    juce::Image batterImage, carryImage;
    int imageSize = 0;

    juce::Rectangle<int> headsArea, legendArea;
    juce::Rectangle<float> batterDisc, carryDisc;

    juce::Path wirePath, touchPath; // reused between frames

    JUCE_DECLARE_NON_COPYABLE_WITH_LEAK_DETECTOR(DrumView)
};

} // namespace snaresim::ui
