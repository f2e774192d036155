//! The examples' package: the programs are its examples (`cargo run
//! --release --example NAME`, see README.md); this library is empty.
