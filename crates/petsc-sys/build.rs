//! Finds the system PETSc with `pkg-config` (module `PETSc`, e.g. Debian's `petsc-dev`) and
//! checks, from its `petscconf.h`, that the installed configuration matches the types declared
//! in `src/lib.rs`: real double-precision scalars, 32-bit `PetscInt` (or 64-bit, selected by
//! `cfg(petsc_int64)`), Open MPI (whose `MPI_Comm` is a pointer). A mismatch stops the build
//! with a message naming the setting, never a silently wrong ABI.

use std::path::PathBuf;
use std::process::Command;

fn pkg_config(args: &[&str]) -> Option<String> {
    let out = Command::new("pkg-config").args(args).output().ok()?;
    out.status
        .success()
        .then(|| String::from_utf8_lossy(&out.stdout).trim().to_owned())
}

fn main() {
    println!("cargo:rerun-if-env-changed=PKG_CONFIG_PATH");
    println!("cargo:rustc-check-cfg=cfg(petsc_int64)");
    println!("cargo:rustc-check-cfg=cfg(petsc_have_mumps)");
    if std::env::var_os("CARGO_FEATURE_PETSC").is_none() {
        return; // the empty crate of the default build
    }
    let module = "PETSc";
    let Some(libs) = pkg_config(&["--libs", module]) else {
        panic!(
            "capstan-petsc-sys: `pkg-config --libs PETSc` failed: install PETSc \
             (Debian/Ubuntu: apt-get install petsc-dev) or set PKG_CONFIG_PATH to its pkgconfig \
             directory; the `petsc` feature of capstan needs it"
        );
    };
    let include = pkg_config(&["--variable=includedir", module])
        .map(PathBuf::from)
        .expect("pkg-config PETSc has no includedir");
    let conf_path = include.join("petscconf.h");
    let conf = std::fs::read_to_string(&conf_path)
        .unwrap_or_else(|e| panic!("cannot read {}: {e}", conf_path.display()));
    println!("cargo:rerun-if-changed={}", conf_path.display());
    let defined = |name: &str| {
        conf.lines().any(|l| {
            let mut w = l.split_whitespace();
            w.next() == Some("#define") && w.next() == Some(name)
        })
    };
    if defined("PETSC_USE_COMPLEX") || !defined("PETSC_USE_REAL_DOUBLE") {
        panic!(
            "capstan-petsc-sys: {} is not a real double-precision build \
             (PetscScalar must be f64: install the `-real` flavour)",
            conf_path.display()
        );
    }
    if defined("PETSC_USE_64BIT_INDICES") {
        println!("cargo:rustc-cfg=petsc_int64");
    }
    if defined("PETSC_HAVE_MUMPS") {
        println!("cargo:rustc-cfg=petsc_have_mumps");
    }
    if !defined("PETSC_HAVE_OMPI_MAJOR_VERSION") {
        // Open MPI's MPI_Comm is a pointer, MPICH's an int: the declarations assume the former.
        panic!(
            "capstan-petsc-sys: {} is not built on Open MPI (MPI_Comm must be a pointer, as \
             with Debian's petsc-dev)",
            conf_path.display()
        );
    }
    let mut lib_dirs = Vec::new();
    let mpi_libs = pkg_config(&["--libs", "ompi-c"]).unwrap_or_else(|| "-lmpi".into());
    for flag in libs.split_whitespace().chain(mpi_libs.split_whitespace()) {
        if let Some(dir) = flag.strip_prefix("-L") {
            println!("cargo:rustc-link-search=native={dir}");
            lib_dirs.push(dir.to_owned());
        } else if let Some(lib) = flag.strip_prefix("-l") {
            println!("cargo:rustc-link-lib=dylib={lib}");
        }
    }
    // For dependents' build scripts and the facade: where the libraries live (an rpath).
    println!("cargo:lib_dirs={}", lib_dirs.join(":"));
    println!("cargo:include={}", include.display());
}
