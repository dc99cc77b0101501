//! Answers the mode decisions have already worked out in a run, by question. A periodic response
//! meets the same configurations cycle after cycle, and a large wall keeps returning to a few (a
//! small cluster sticking to the wall, slipping, sticking again). Questions about many blocks
//! hold a copy of most of the wall each, so only the latest [`LARGE_KEPT`] of them are kept.

use rustc_hash::FxHashMap;
use std::collections::VecDeque;
use std::hash::Hash;
use std::rc::Rc;

/// Questions of this many blocks or more are large.
pub const LARGE_FROM: usize = 256;

/// Large questions kept (the oldest is forgotten first).
const LARGE_KEPT: usize = 32;

/// Remembered answers.
pub struct Memo<K, V> {
    /// Keyed by a fast hash: a decision's question is hashed at every event.
    map: FxHashMap<Rc<K>, V>,
    large: VecDeque<Rc<K>>,
}

impl<K: Hash + Eq, V> Memo<K, V> {
    /// Nothing remembered.
    pub fn new() -> Memo<K, V> {
        Memo {
            map: FxHashMap::default(),
            large: VecDeque::new(),
        }
    }

    /// The answer to `question`, if worked out.
    pub fn get(&self, question: &K) -> Option<&V> {
        self.map.get(question)
    }

    /// The answer to `question`, if worked out, to amend.
    pub fn get_mut(&mut self, question: &K) -> Option<&mut V> {
        self.map.get_mut(question)
    }

    /// Remembers an answer; `blocks` is the size of the question.
    pub fn insert(&mut self, question: K, answer: V, blocks: usize) {
        let question = Rc::new(question);
        if blocks >= LARGE_FROM {
            self.large.push_back(Rc::clone(&question));
            if self.large.len() > LARGE_KEPT {
                let oldest = self.large.pop_front().expect("more than kept");
                self.map.remove(&*oldest);
            }
        }
        self.map.insert(question, answer);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn small_answers_stay_and_large_ones_are_forgotten_oldest_first() {
        let mut memo: Memo<u32, u32> = Memo::new();
        memo.insert(0, 100, 5);
        for k in 1..=(LARGE_KEPT as u32 + 2) {
            memo.insert(k, k * 10, LARGE_FROM);
        }
        assert_eq!(memo.get(&0), Some(&100));
        assert_eq!(memo.get(&1), None);
        assert_eq!(memo.get(&2), None);
        assert_eq!(memo.get(&3), Some(&30));
        assert_eq!(
            memo.get(&(LARGE_KEPT as u32 + 2)),
            Some(&((LARGE_KEPT as u32 + 2) * 10))
        );
        assert_eq!(memo.map.len(), LARGE_KEPT + 1);
    }
}
