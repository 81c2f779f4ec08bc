//! The driver: rayon over a plan's points, one writer thread owning the sink, failure
//! isolation, resume (skip done ids), sharding, Ctrl-C.

pub mod adapters;
pub mod driver;
pub mod observer;
pub mod progress;
pub mod shard;
pub mod single;
pub mod traits;

pub use adapters::{ModelSimulator, StoreEncoder, StoreSink};
pub use driver::{
    build_pool, check_finite, check_finite_for, prepare_bats, prepare_bats_alongside, run_plan,
    PreparedBats, RunError, RunOptions, RunReport,
};
pub use observer::{Observer, Phase, SharedObserver, Silent};
pub use shard::{estimate_cost, shard_range, CostModel, Shard, MAX_SHARDS};
pub use traits::{AsIs, Encode, Simulator, Sink};
