//! A wall with its graph: what every run takes, built and checked once (the wall's own checks,
//! then the graph's), so that a wall and a graph that do not belong together cannot meet.

use crate::error::{Error, WallError};
use crate::topology::Topology;
use crate::wall::Wall;
use std::path::Path;

/// A checked wall and its support and contact graph.
#[derive(Debug, Clone)]
pub struct Model {
    wall: Wall,
    topology: Topology,
}

impl Model {
    /// The model of a wall: its graph built and checked (floating blocks, blocks that would
    /// topple at rest, friction keys that name no joint).
    pub fn new(wall: Wall) -> Result<Model, WallError> {
        let topology = Topology::new(&wall)?;
        Ok(Model { wall, topology })
    }

    /// Reads a wall file (RON); errors name the file.
    pub fn from_file(path: impl AsRef<Path>) -> Result<Model, Error> {
        let path = path.as_ref();
        let (wall, topology) = crate::topology::load(path)?;
        Ok(Model { wall, topology })
    }

    /// A wall written in RON.
    pub fn from_ron_str(text: &str) -> Result<Model, WallError> {
        Model::new(Wall::from_ron_str(text)?)
    }

    /// The wall.
    pub fn wall(&self) -> &Wall {
        &self.wall
    }

    /// Its graph.
    pub fn topology(&self) -> &Topology {
        &self.topology
    }
}
