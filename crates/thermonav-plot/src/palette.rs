//! Colours: the Okabe-Ito palette, distinguishable with the common colour-vision deficiencies.

/// A CSS colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Color(pub &'static str);

/// The series colours, in order of use.
pub const SERIES: [Color; 7] = [
    Color("#0072b2"),
    Color("#e69f00"),
    Color("#009e73"),
    Color("#d55e00"),
    Color("#cc79a7"),
    Color("#56b4e9"),
    Color("#000000"),
];

/// Dark grey for frames, text and neutral legend swatches.
pub const INK: Color = Color("#333333");
/// Light grey for grid lines.
pub const GRID: Color = Color("#dddddd");
/// Pale grey for grid lines between decades.
pub const MINOR_GRID: Color = Color("#f0f0f0");
/// Mid grey for secondary lines (the processes of a composite model).
pub const MUTED: Color = Color("#999999");
/// Fill of highlighted x intervals (e.g. GNSS outages).
pub const HIGHLIGHT: Color = Color("#f4a582");

/// The colour of the `index`-th series (the palette repeats).
pub fn series_color(index: usize) -> Color {
    SERIES[index % SERIES.len()]
}
