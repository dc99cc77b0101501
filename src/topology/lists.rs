//! Lists per block kept back to back in one vector: the event engine walks the supports and
//! faces of every block of a large group at each decision, and one allocation per block put
//! each list in a place of its own in memory.

use std::ops::Index;

/// One list per block, block i's at `items[first[i]..first[i + 1]]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Lists<T> {
    first: Vec<usize>,
    items: Vec<T>,
}

impl<T> From<Vec<Vec<T>>> for Lists<T> {
    fn from(lists: Vec<Vec<T>>) -> Lists<T> {
        let mut first = Vec::with_capacity(lists.len() + 1);
        first.push(0);
        let mut items = Vec::with_capacity(lists.iter().map(Vec::len).sum());
        for list in lists {
            items.extend(list);
            first.push(items.len());
        }
        Lists { first, items }
    }
}

impl<T> Index<usize> for Lists<T> {
    type Output = [T];

    fn index(&self, i: usize) -> &[T] {
        &self.items[self.first[i]..self.first[i + 1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_list_comes_back_as_it_was_given() {
        let given = vec![vec![1, 2], vec![], vec![3], vec![]];
        let lists = Lists::from(given.clone());
        for (i, list) in given.iter().enumerate() {
            assert_eq!(&lists[i], list.as_slice());
        }
    }
}
