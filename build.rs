//! Builds the Embree anchor of `raysandbox bench --throughput`
//! (src/bench/embree.c) when the `embree` feature is on; the default and
//! the web builds compile nothing here.

fn main() {
    println!("cargo:rerun-if-changed=build.rs");
    #[cfg(feature = "embree")]
    {
        println!("cargo:rerun-if-changed=src/bench/embree.c");
        cc::Build::new()
            .file("src/bench/embree.c")
            .opt_level(2)
            .compile("raysandbox_embree");
        println!("cargo:rustc-link-lib=embree3");
    }
}
