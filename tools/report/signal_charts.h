// The report's pictures of the block's signals (time waveform, mesh-frequency zooms,
// contribution spectra, synchronous averages), as standalone inline SVG fragments written by
// hand, one chart per function.
//
// Elements a test or a reader may look for carry a class and data-* attributes:
// path.waveform (data-samples), line.mesh-cursor and line.sideband-cursor (data-shaft,
// data-order = signed k, data-hz), circle.spectrum-peak (data-hz, data-value),
// path.spectrum-line (data-series), path.tsa-line (data-series). All text is XML-escaped.
#pragma once

#include <string>
#include <vector>

#include "tools/report/report_data.h"

namespace gearpath::tools {

// Time waveform from t0 (ms) on a y axis -y_abs_max..y_abs_max in the signal's unit; each
// pixel column shows the min..max of its samples, so no impact is lost to decimation.
std::string WaveformSvg(const ReportWaveform& wave, double y_abs_max);

// Amplitude spectrum (dB re 1 unit) within +/-(orders + 1) x the faster shaft's rate of the
// mesh frequency: a solid cursor at the mesh frequency, dashed cursors at mesh +/- k x each of
// the mesh's shaft rates (k = 1..orders, colour per shaft) and the largest bin marked.
std::string MeshZoomSvg(const ReportSpectrum& spectrum, const ReportMesh& mesh,
                        const std::vector<ReportShaft>& shafts, int orders);

// Each path's contribution spectrum at the indicator channel (thin, colour per path), their sum
// (dashed red) and the measured spectrum (black), dB re 1 unit over [lo_hz, hi_hz]; each pixel
// column shows its largest bin.
std::string ContributionSpectraSvg(const ReportSpectrum& measured,
                                   const std::vector<ReportSpectrum>& paths,
                                   const std::vector<std::string>& path_names,
                                   const ReportSpectrum& sum, double lo_hz, double hi_hz);

// Each path's identified bearing-force amplitude spectrum (colour per path), dB re 1 unit over
// [lo_hz, hi_hz], peak hold per pixel column, with circle.force-peak (data-path, data-hz,
// data-value) on each path's largest bin in the range.
std::string ForceSpectraSvg(const std::vector<ReportSpectrum>& forces,
                            const std::vector<std::string>& path_names, double lo_hz,
                            double hi_hz);

// One revolution of a shaft's synchronous average: measured (black) and reconstructed (blue)
// against shaft angle (degrees), y axis -y_abs_max..y_abs_max in `unit`.
std::string SynchronousAverageSvg(const ReportSynchronousAverage& tsa, const std::string& unit,
                                  double y_abs_max);

}  // namespace gearpath::tools
