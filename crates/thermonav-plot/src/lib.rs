//! Figures of thermonav as standalone SVG documents, and self-contained HTML pages.
//!
//! The SVG written here has inline styles only, a font-family stack of generic fonts, no
//! script and no external reference, so a file opens the same way offline in any browser.
//!
//! - [`chart`]: panels with axes, grid, legend and data layers, laid out into a figure.
//! - [`scale`]: linear and log₁₀ axes, their pixel mapping and ticks.
//! - [`figures`]: the project's figures (Allan deviation, correlation time versus
//!   temperature, autocorrelation, navigation errors, trajectory, bias against
//!   temperature), each a function of typed data returning an SVG string.
//! - [`html`]: a self-contained HTML page assembled from sections.
//! - [`png`]: the same figures as PNG, rasterised in pure Rust with a bundled font.

pub mod chart;
pub mod figures;
pub mod html;
pub mod palette;
pub mod png;
pub mod scale;
pub mod svg;

#[cfg(test)]
mod parsed_svg;
