#include "DrumView.h"

#include <algorithm>
#include <cmath>

namespace snaresim::ui
{

namespace
{
// The colour scale follows the snapshot's peak and otherwise decays by this factor per frame
// (30 frames/s: halves in about 0.7 s), so a quiet tail keeps filling the colour range.
constexpr float scaleDecayPerFrame = 0.968f;
// Below this (m) the drum counts as at rest: numerical residue stays white.
constexpr float minimumScale_m = 2.0e-8f;
// Colour = map(sign(t) |t|^gamma): small displacements stay visible next to the peak.
constexpr float colourGamma = 0.7f;

constexpr int maxImageSize = 320;

// Red-blue diverging stops (ColorBrewer RdBu), from -1 (down) to +1 (up).
const juce::Colour mapStops[] = { juce::Colour(0xff2166ac), juce::Colour(0xff67a9cf), juce::Colour(0xfff7f7f7), juce::Colour(0xffef8a62),
                                  juce::Colour(0xffb2182b) };

juce::String formatLength(float metres)
{
    // Three significant digits in nm, um or mm.
    const auto withUnit = [](float v, const char* unit) {
        const float a = std::abs(v);
        const auto number = a >= 100.0f ? juce::String(juce::roundToInt(v)) : juce::String(v, a >= 10.0f ? 1 : 2);
        return number + juce::String(juce::CharPointer_UTF8(unit));
    };

    const float a = std::abs(metres);
    if (a < 1.0e-6f)
        return withUnit(metres * 1.0e9f, " nm");
    if (a < 1.0e-3f)
        return withUnit(metres * 1.0e6f, " \xc2\xb5m");
    return withUnit(metres * 1.0e3f, " mm");
}
} // namespace

juce::Colour DrumView::colourFor(float t)
{
    t = juce::jlimit(-1.0f, 1.0f, t);
    const float pos = (t + 1.0f) * 2.0f; // 0 .. 4 over the five stops
    const int i = juce::jlimit(0, 3, (int) std::floor(pos));
    return mapStops[i].interpolatedWith(mapStops[i + 1], pos - (float) i);
}

namespace
{
juce::Colour shapedColour(float t) { return DrumView::colourFor(std::copysign(std::pow(std::abs(t), colourGamma), t)); }
} // namespace

DrumView::DrumView(EditorLookAndFeel& lookToUse) : look(lookToUse)
{
    // The LUT is indexed by the linear t in [-1, 1] and holds the colour of the gamma-shaped t.
    const int n = (int) lut.size();
    for (int k = 0; k < n; ++k)
    {
        const float t = (float) k / (float) (n - 1) * 2.0f - 1.0f;
        lut[(size_t) k] = shapedColour(t).getPixelARGB();
    }

    setOpaque(false);
    setTitle("Drum picture");
    setDescription("Batter and carry heads with the snare wires");
}

void DrumView::setNotice(const juce::String& text)
{
    if (text == notice)
        return;
    notice = text;
    repaint();
}

void DrumView::update(const DrumSnapshot& snapshot)
{
    shown = snapshot;
    hasSnapshot = true;

    headScale = std::max({ snapshot.peakDisplacement, headScale * scaleDecayPerFrame, minimumScale_m });

    float wirePeak = 0.0f;
    const int wires = std::clamp(snapshot.numWires, 0, DrumSnapshot::maxWires);
    for (int k = 0; k < wires * DrumSnapshot::wirePoints; ++k)
        wirePeak = std::max(wirePeak, std::abs(snapshot.wire[(size_t) k]));
    wireScale = std::max({ wirePeak, wireScale * scaleDecayPerFrame, minimumScale_m });

    renderHeads();
    repaint();
}

void DrumView::resized()
{
    auto area = getLocalBounds();
    area.removeFromTop(look.panelTitleHeight());
    area = area.reduced(look.pxi(12.0f), 0).withTrimmedBottom(look.pxi(8.0f));

    legendArea = area.removeFromRight(look.pxi(70.0f));
    area.removeFromRight(look.pxi(8.0f));
    headsArea = area;

    const float captionH = look.px(20.0f);
    const float gap = look.px(18.0f);
    const auto discs = headsArea.toFloat().withTrimmedBottom(captionH);
    const float diameter = std::max(8.0f, std::min(discs.getHeight(), (discs.getWidth() - gap) * 0.5f));
    const float totalW = diameter * 2.0f + gap;
    const float x0 = discs.getX() + (discs.getWidth() - totalW) * 0.5f;
    const float y0 = discs.getY() + (discs.getHeight() - diameter) * 0.5f;

    batterDisc = { x0, y0, diameter, diameter };
    carryDisc = { x0 + diameter + gap, y0, diameter, diameter };

    const int wanted = std::clamp(juce::roundToInt(diameter), 16, maxImageSize);
    if (wanted != imageSize)
    {
        imageSize = wanted;
        batterImage = juce::Image(juce::Image::ARGB, imageSize, imageSize, true);
        carryImage = juce::Image(juce::Image::ARGB, imageSize, imageSize, true);
        renderHeads();
    }
}

void DrumView::renderHeads()
{
    if (imageSize <= 0)
        return;

    renderHead(shown.batter, batterImage);
    renderHead(shown.carry, carryImage);
}

void DrumView::renderHead(const std::array<float, DrumSnapshot::raster * DrumSnapshot::raster>& raster, juce::Image& image) const
{
    constexpr int P = DrumSnapshot::raster;
    const int N = image.getWidth();
    const float toIndex = (float) (lut.size() - 1) * 0.5f;
    const float invScale = hasSnapshot && headScale > 0.0f ? 1.0f / headScale : 0.0f;
    const float rasterPerPixel = (float) P / (float) N;

    juce::Image::BitmapData data(image, juce::Image::BitmapData::writeOnly);

    for (int y = 0; y < N; ++y)
    {
        // Bilinear interpolation between raster points (centres at (j + 0.5) / P of the square).
        const float v = ((float) y + 0.5f) * rasterPerPixel - 0.5f;
        const int j0 = std::clamp((int) std::floor(v), 0, P - 2);
        const float fv = std::clamp(v - (float) j0, 0.0f, 1.0f);
        const float* row0 = raster.data() + j0 * P;
        const float* row1 = row0 + P;

        for (int x = 0; x < N; ++x)
        {
            const float u = ((float) x + 0.5f) * rasterPerPixel - 0.5f;
            const int i0 = std::clamp((int) std::floor(u), 0, P - 2);
            const float fu = std::clamp(u - (float) i0, 0.0f, 1.0f);

            const float top = row0[i0] + (row0[i0 + 1] - row0[i0]) * fu;
            const float bottom = row1[i0] + (row1[i0 + 1] - row1[i0]) * fu;
            const float w = top + (bottom - top) * fv;

            const float t = std::clamp(w * invScale, -1.0f, 1.0f);
            const auto index = (size_t) juce::roundToInt((t + 1.0f) * toIndex);
            *reinterpret_cast<juce::PixelARGB*>(data.getPixelPointer(x, y)) = lut[index];
        }
    }
}

void DrumView::paint(juce::Graphics& g)
{
    look.drawPanel(g, getLocalBounds(), "Live drum");

    paintHead(g, batterDisc, batterImage);
    paintHead(g, carryDisc, carryImage);
    paintWires(g, carryDisc);

    // Captions.
    const auto captionFont = look.font(12.5f);
    g.setFont(captionFont);
    const int captionH = look.pxi(20.0f);
    const auto captionFor = [&](juce::Rectangle<float> disc) {
        return juce::Rectangle<int>(juce::roundToInt(disc.getX() - look.px(20.0f)), headsArea.getBottom() - captionH,
                                    juce::roundToInt(disc.getWidth() + look.px(40.0f)), captionH);
    };

    g.setColour(Palette::textDim);
    g.drawFittedText("Batter head (top)", captionFor(batterDisc), juce::Justification::centred, 1);
    g.drawFittedText(shown.snaresEngaged || ! hasSnapshot ? "Carry head + snare wires" : "Carry head (snares off)", captionFor(carryDisc),
                     juce::Justification::centred, 1);

    if (notice.isNotEmpty())
    {
        g.setColour(Palette::accent);
        g.setFont(look.font(11.5f));
        // one line each (the air box's, Quality's)
        const int lines = juce::StringArray::fromLines(notice).size();
        g.drawFittedText(notice, getLocalBounds().withHeight(look.panelTitleHeight() * lines).withTrimmedRight(look.pxi(12.0f)),
                         juce::Justification::topRight, lines);
    }
    else if (! hasSnapshot)
    {
        g.setColour(Palette::textFaint);
        g.setFont(look.font(11.5f));
        g.drawText("Waiting for audio", getLocalBounds().withHeight(look.panelTitleHeight()).withTrimmedRight(look.pxi(12.0f)),
                   juce::Justification::centredRight, true);
    }

    paintLegend(g, legendArea);
}

void DrumView::paintHead(juce::Graphics& g, juce::Rectangle<float> disc, const juce::Image& image) const
{
    if (disc.getWidth() < 4.0f || ! image.isValid())
        return;

    // Shadow, the head (the image as the fill of an ellipse: smooth edge), the rim.
    g.setColour(juce::Colours::black.withAlpha(0.35f));
    g.fillEllipse(disc.expanded(look.px(3.0f)).translated(0.0f, look.px(1.5f)));

    const auto transform =
        juce::AffineTransform::scale(disc.getWidth() / (float) image.getWidth(), disc.getHeight() / (float) image.getHeight())
            .translated(disc.getX(), disc.getY());
    {
        juce::Graphics::ScopedSaveState save(g);
        g.setImageResamplingQuality(juce::Graphics::mediumResamplingQuality);
        g.setFillType(juce::FillType(image, transform));
        g.fillEllipse(disc);
    }

    g.setColour(juce::Colour(0xff9097a3));
    g.drawEllipse(disc, look.px(2.5f));
    g.setColour(juce::Colour(0xff3b3f48));
    g.drawEllipse(disc.expanded(look.px(1.75f)), look.px(1.0f));
}

void DrumView::paintWires(juce::Graphics& g, juce::Rectangle<float> disc)
{
    const int wires = std::clamp(shown.numWires, 0, DrumSnapshot::maxWires);
    if (! hasSnapshot || wires == 0 || disc.getWidth() < 8.0f)
        return;

    constexpr int Q = DrumSnapshot::wirePoints;
    const float R = disc.getWidth() * 0.5f;
    const auto c = disc.getCentre();
    const float length = std::clamp(shown.wireLength_frac, 0.0f, 1.0f) * 2.0f * R;
    const float x0 = c.x - 0.5f * length;

    // Deflection drawn across the wire, at most about one and a half wire pitches.
    const float pitch = wires > 1 ? std::abs(shown.wireY_frac[1] - shown.wireY_frac[0]) * R : look.px(4.0f);
    const float amplitude = std::clamp(pitch * 1.5f, look.px(2.0f), look.px(8.0f));
    const float gain = wireScale > 0.0f ? amplitude / wireScale : 0.0f;

    wirePath.clear();
    touchPath.clear();

    for (int i = 0; i < wires; ++i)
    {
        const float y = c.y + shown.wireY_frac[(size_t) i] * R;
        const float* w = shown.wire.data() + i * Q;
        const unsigned char* touch = shown.touching.data() + i * Q;
        bool inTouch = false;

        for (int q = 0; q < Q; ++q)
        {
            const juce::Point<float> p { x0 + length * (float) q / (float) (Q - 1), y - w[q] * gain };

            if (q == 0)
                wirePath.startNewSubPath(p);
            else
                wirePath.lineTo(p);

            // Highlight each segment with a touching end.
            if (q > 0 && (touch[q] != 0 || touch[q - 1] != 0))
            {
                if (! inTouch)
                    touchPath.startNewSubPath({ x0 + length * (float) (q - 1) / (float) (Q - 1), y - w[q - 1] * gain });
                touchPath.lineTo(p);
                inTouch = true;
            }
            else
                inTouch = false;
        }
    }

    const bool engaged = shown.snaresEngaged;
    g.setColour(juce::Colour(0xff2a2e37).withAlpha(engaged ? 0.9f : 0.3f));
    g.strokePath(wirePath, juce::PathStrokeType(std::max(1.0f, look.px(1.0f))));

    if (engaged && ! touchPath.isEmpty())
    {
        g.setColour(juce::Colour(0xffffb52e));
        g.strokePath(touchPath, juce::PathStrokeType(std::max(1.2f, look.px(1.5f))));
    }

    if (! engaged)
    {
        // A note over the head: the wires are thrown off.
        const auto note = juce::String("Snares thrown off");
        const auto font = look.font(12.5f, true);
        const float w = (float) font.getStringWidth(note) + look.px(20.0f);
        const float h = look.px(22.0f);
        const auto pill = juce::Rectangle<float>(w, h).withCentre({ c.x, c.y + R * 0.55f });
        g.setColour(Palette::background.withAlpha(0.85f));
        g.fillRoundedRectangle(pill, h * 0.5f);
        g.setColour(Palette::caution);
        g.setFont(font);
        g.drawText(note, pill, juce::Justification::centred, false);
    }
}

void DrumView::paintLegend(juce::Graphics& g, juce::Rectangle<int> area) const
{
    if (area.getHeight() < 40)
        return;

    const int labelH = look.pxi(16.0f);
    auto bar = area.withTrimmedTop(labelH + look.pxi(4.0f)).withTrimmedBottom(look.pxi(20.0f) + labelH + look.pxi(4.0f));
    bar = bar.withWidth(look.pxi(12.0f));
    const auto barF = bar.toFloat();

    // The gradient of the map as shown (gamma included), red (up) at the top.
    juce::ColourGradient gradient(shapedColour(1.0f), barF.getX(), barF.getY(), shapedColour(-1.0f), barF.getX(), barF.getBottom(), false);
    for (int k = 1; k < 16; ++k)
    {
        const float p = (float) k / 16.0f;
        gradient.addColour(p, shapedColour(1.0f - 2.0f * p));
    }
    g.setGradientFill(gradient);
    g.fillRect(barF);
    g.setColour(Palette::panelOutline);
    g.drawRect(barF, 1.0f);

    const int textX = bar.getRight() + look.pxi(6.0f);
    const int textW = area.getRight() - textX;
    g.setFont(look.font(11.0f));

    const float scale = hasSnapshot ? headScale : 0.0f;
    g.setColour(Palette::text);
    g.drawText("+" + formatLength(scale), area.getX(), bar.getY() - labelH - look.pxi(3.0f), area.getWidth(), labelH,
               juce::Justification::centredLeft, false);
    g.drawText(juce::String(juce::CharPointer_UTF8("\xe2\x88\x92")) + formatLength(scale), area.getX(), bar.getBottom() + look.pxi(3.0f),
               area.getWidth(), labelH, juce::Justification::centredLeft, false);

    g.setColour(Palette::textDim);
    g.drawText("up", textX, bar.getY(), textW, labelH, juce::Justification::centredLeft, false);
    g.drawText("rest", textX, bar.getCentreY() - labelH / 2, textW, labelH, juce::Justification::centredLeft, false);
    g.drawText("down", textX, bar.getBottom() - labelH, textW, labelH, juce::Justification::centredLeft, false);

    // Wire key under the bar.
    const int keyY = bar.getBottom() + labelH + look.pxi(8.0f);
    const auto swatch = juce::Rectangle<float>((float) area.getX(), (float) keyY + look.px(6.0f), look.px(12.0f), look.px(3.0f));
    g.setColour(juce::Colour(0xffffb52e));
    g.fillRect(swatch);
    g.setColour(Palette::textDim);
    g.drawText("touching", juce::roundToInt(swatch.getRight()) + look.pxi(4.0f), keyY,
               area.getRight() - juce::roundToInt(swatch.getRight()), look.pxi(16.0f), juce::Justification::centredLeft, false);
}

} // namespace snaresim::ui
