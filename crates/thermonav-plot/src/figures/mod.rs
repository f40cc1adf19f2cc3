//! The project's figures: each a function of typed data returning a standalone SVG string.
