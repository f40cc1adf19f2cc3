//! Integration tests of the thermonav library against independent oracles.

mod gauss_markov;
