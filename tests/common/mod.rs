//! Shared helpers for the physics tests.
#![allow(dead_code)]

use batstudy::model::spec::*;

/// The base case: R161, default ball (linear hysteresis, e = 0.5, 40 m/s), free ends.
pub fn base_spec(z: f64) -> CollisionSpec {
    CollisionSpec::base_case(z)
}

pub fn elastic() -> BallLaw {
    BallLaw {
        kind: BallLawKind::Elastic,
        ..BallLaw::default()
    }
}

/// The batstudy binary with `args`, its standard output dropped and its errors kept.
pub fn batstudy_command(args: &[&str]) -> std::process::Command {
    let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_batstudy"));
    c.args(args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped());
    c
}

/// Run the batstudy binary with `args` to completion and require success (its stderr in
/// the failure message).
pub fn batstudy_ok(args: &[&str]) {
    let out = batstudy_command(args).output().unwrap();
    assert!(
        out.status.success(),
        "batstudy {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&out.stderr)
    );
}

/// Every stored record of a results file: its place, id and bat, and a hash of its outcome
/// as exact text (Debug of f64 is its shortest round-trip form): two files with equal lists
/// hold the same data.
pub fn stored_records(path: &std::path::Path) -> Vec<String> {
    batstudy::store::read_results(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .records
        .iter()
        .map(|r| {
            // The outcome's scalars as exact text (Debug of f64 is its shortest round-trip
            // form, -0 and NaN included), its histories as their values' bits: the texts of
            // every history value of a file were most of the time of the tests that use this.
            let mut digest = std::hash::DefaultHasher::new();
            let mut result = r.result.clone();
            if let Ok(outcome) = &mut result {
                if let Some(history) = outcome.history.take() {
                    hash_history(&history, &mut digest);
                }
            }
            std::hash::Hash::hash(&format!("{result:?}"), &mut digest);
            let digest = std::hash::Hasher::finish(&digest);
            format!("{} {} {} {digest:016x}", r.index, r.id, r.bat)
        })
        .collect()
}

/// Every value of a history, by its bits (the destructuring names every field, so that a new
/// one cannot be left out).
fn hash_history(history: &batstudy_physics::outcome::History, digest: &mut impl std::hash::Hasher) {
    use batstudy_physics::outcome::{History, ModalHistory};
    let History {
        force,
        compression,
        ball_velocity,
        displacement,
        rigid_translation,
        rigid_rotation,
        hoop_displacement,
        trajectory_x,
        trajectory_y,
        trajectory_z,
        modal:
            ModalHistory {
                modes,
                coordinate,
                bat_load,
                static_shape,
            },
    } = history;
    digest.write_usize(*modes);
    for values in [
        force,
        compression,
        ball_velocity,
        displacement,
        rigid_translation,
        rigid_rotation,
        hoop_displacement,
        trajectory_x,
        trajectory_y,
        trajectory_z,
        coordinate,
        bat_load,
        static_shape,
    ] {
        digest.write_usize(values.len());
        values.iter().for_each(|x| digest.write_u64(x.to_bits()));
    }
}

extern "C" {
    // libhdf5 ≥ 1.10.5; declared here so as not to depend on the -sys crate's version gates
    fn H5Dget_num_chunks(dset: i64, fspace: i64, nchunks: *mut u64) -> i32;
    fn H5Dget_chunk_info(
        dset: i64,
        fspace: i64,
        index: u64,
        offset: *mut u64,
        filter_mask: *mut u32,
        addr: *mut u64,
        size: *mut u64,
    ) -> i32;
}

/// (chunk offset, file address, stored bytes) of one chunk of a dataset.
pub type ChunkPlace = (Vec<u64>, u64, u64);

/// Every allocated chunk of a chunked dataset, in HDF5's order (unfiltered: filter mask 0).
pub fn chunk_places(ds: &hdf5::Dataset) -> Vec<ChunkPlace> {
    let space = ds.space().unwrap();
    hdf5::sync::sync(|| {
        let mut n = 0u64;
        assert!(unsafe { H5Dget_num_chunks(ds.id(), space.id(), &mut n) } >= 0);
        (0..n)
            .map(|i| {
                let mut offset = vec![0u64; ds.ndim()];
                let (mut mask, mut addr, mut size) = (0u32, 0u64, 0u64);
                let r = unsafe {
                    H5Dget_chunk_info(
                        ds.id(),
                        space.id(),
                        i,
                        offset.as_mut_ptr(),
                        &mut mask,
                        &mut addr,
                        &mut size,
                    )
                };
                assert!(r >= 0 && mask == 0, "chunk {i} of {}", ds.name());
                (offset, addr, size)
            })
            .collect()
    })
}

/// xorshift64* (Vigna 2016): a small, seeded generator for test inputs, the same on every
/// platform.
pub struct Rng(pub u64);

impl Rng {
    pub fn next(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// Uniform in 0..n.
    pub fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }

    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> f64 {
        (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A collision's energy closes: the diagnostics' final energy (every part, friction and
/// damping included) is the initial energy to within `tolerance` (relative).
pub fn assert_energy_closes(
    outcome: &batstudy::model::outcome::Outcome,
    diagnostics: &batstudy::model::collision::wave::Diagnostics,
    tolerance: f64,
    what: &str,
) {
    assert!(
        (diagnostics.energy_final / outcome.energy.initial - 1.0).abs() < tolerance,
        "{what}: {} vs {}",
        diagnostics.energy_final,
        outcome.energy.initial
    );
}
