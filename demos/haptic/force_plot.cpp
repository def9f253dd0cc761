#include "force_plot.h"

#include "plot_canvas.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace unidist::haptic {
namespace {

constexpr int kWidth = 900, kHeight = 420;
constexpr int kLeft = 90, kRight = 20, kTop = 44, kBottom = 48;  // the plot area's margins
constexpr Rgb kWhite{255, 255, 255}, kBlack{0, 0, 0}, kGrid{225, 225, 225};
constexpr Rgb kRed{220, 40, 40}, kGreen{30, 150, 60}, kBlue{40, 80, 220};

/// A tick spacing of 1, 2 or 5 × 10^k giving about `count` intervals over `range`.
double niceStep(double range, int count) {
  const double raw = range / count, power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * power >= raw) return m * power;
  return 10 * power;
}

std::string tickLabel(double v, double step) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", std::max(0, -static_cast<int>(std::floor(std::log10(step)))), v);
  return std::string(buf) == "-0" ? "0" : buf;
}

/// Ticks with labels and grid lines on both axes of the plot area [x0, x1] × [y0, y1] (pixels).
template <class ToX, class ToY>
void axes(PlotCanvas& c, double tMax, double fLo, double fHi, ToX toX, ToY toY) {
  const double tStep = niceStep(tMax, 8), fStep = niceStep(fHi - fLo, 6);
  for (double t = 0; t <= tMax + 1e-9 * tMax; t += tStep) {
    const double x = toX(t);
    c.line(x, kTop, x, kHeight - kBottom, kGrid);
    const std::string label = tickLabel(t, tStep);
    c.text(static_cast<int>(x) - PlotCanvas::textWidth(label) / 2, kHeight - kBottom + 8, label, kBlack);
  }
  for (double f = std::ceil(fLo / fStep) * fStep; f <= fHi; f += fStep) {
    const double y = toY(f);
    c.line(kLeft, y, kWidth - kRight, y, std::abs(f) < 1e-9 * fStep ? Rgb{150, 150, 150} : kGrid);
    const std::string label = tickLabel(f, fStep);
    c.text(kLeft - 8 - PlotCanvas::textWidth(label), static_cast<int>(y) - 5, label, kBlack);
  }
  c.line(kLeft, kTop, kLeft, kHeight - kBottom, kBlack);
  c.line(kLeft, kHeight - kBottom, kWidth - kRight, kHeight - kBottom, kBlack);
  c.text(kWidth - kRight - PlotCanvas::textWidth("TIME (S)"), kHeight - 18, "time (s)", kBlack);
  c.text(8, kTop - 18, "force", kBlack);
}

}  // namespace

void writeForcePlot(const std::string& path, const std::string& title, const std::vector<Eigen::Vector3d>& force,
                    double timeStep) {
  double fLo = 0, fHi = 0;
  for (const Eigen::Vector3d& f : force) {
    fLo = std::min(fLo, f.minCoeff());
    fHi = std::max(fHi, f.norm());
  }
  if (fHi - fLo <= 0) fHi = 1;  // no force at all: still a readable empty plot
  const double pad = 0.05 * (fHi - fLo);
  fLo -= fLo < 0 ? pad : 0;
  fHi += pad;
  const double tMax = std::max(timeStep, timeStep * static_cast<double>(force.size() > 1 ? force.size() - 1 : 1));
  const auto toX = [&](double t) { return kLeft + (kWidth - kLeft - kRight) * t / tMax; };
  const auto toY = [&](double f) { return kTop + (kHeight - kTop - kBottom) * (fHi - f) / (fHi - fLo); };

  PlotCanvas c(kWidth, kHeight, kWhite);
  axes(c, tMax, fLo, fHi, toX, toY);
  // Components first, |F| on top: it is the curve a reader follows.
  const struct {
    int component;  // 0..2, or 3 for |F|
    Rgb colour;
    const char* label;
  } curves[] = {{0, kRed, "Fx"}, {1, kGreen, "Fy"}, {2, kBlue, "Fz"}, {3, kBlack, "|F|"}};
  const auto value = [&](std::size_t i, int component) {
    return component == 3 ? force[i].norm() : force[i][component];
  };
  int legendX = kWidth - kRight - 4 * 70;
  for (const auto& curve : curves) {
    for (std::size_t i = 1; i < force.size(); ++i)
      c.line(toX(timeStep * static_cast<double>(i - 1)), toY(value(i - 1, curve.component)),
             toX(timeStep * static_cast<double>(i)), toY(value(i, curve.component)), curve.colour,
             curve.component == 3 ? 2 : 1);
    c.line(legendX, kTop - 14, legendX + 24, kTop - 14, curve.colour, 3);
    c.text(legendX + 30, kTop - 19, curve.label, curve.colour);
    legendX += 70;
  }
  c.text(kLeft, 10, title, kBlack);
  c.writePng(path);
}

}  // namespace unidist::haptic
