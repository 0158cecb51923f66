//! The README's Rapier program is `examples/readme.rs`, word for word, so
//! that what the README shows is built and run (as the example,
//! `cargo run --release --example readme`, and as the doctest of the
//! crate's front page, which includes the file).

#[test]
fn the_readme_program_is_the_example() {
    let readme = include_str!("../README.md");
    let example = include_str!("../examples/readme.rs");
    let start = readme.find("```rust\n").expect("the README has a Rust block") + "```rust\n".len();
    let block = &readme[start..start + readme[start..].find("```").expect("the block ends")];
    assert_eq!(
        block, example,
        "the README's program and examples/readme.rs differ"
    );
}
