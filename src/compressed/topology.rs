//! [`Topology`]: the nodes of one compressed quadtree (exercise 14.5) as an arena, with the
//! construction from sorted keys and the two local edits every update is made of.
//!
//! A node is a [`DeepCell`]: the root cell, a cell in which the stored keys fall into at least
//! two children ("branching"), or a leaf, the finest cell (level 64) of one stored [`DeepKey`].
//! Children hang in a singly linked list sorted by the child quadrant of their parent they lie
//! in (Morton order), so a node costs a fixed 32 + 8D bytes whatever the branching.
//!
//! - [`Topology::from_sorted`]: the stack construction over Morton-sorted keys (exercise 14.5,
//!   second part): keep the rightmost path on a stack; for the next key, pop every node deeper
//!   than the level at which it parts from the previous key, and insert the branching cell there
//!   if it is missing. Each node is pushed and popped once: O(n) after the sort.
//! - [`Topology::insert`]: below the deepest node containing the key, add a leaf, and a
//!   branching node where the leaf parts from the sibling already in its quadrant. O(2^D).
//! - [`Topology::remove_leaf`]: unlink a leaf, and splice out its parent when one child is left.
//!   O(2^D).
//!
//! Both edits keep the tree *canonical*: the nodes are exactly the root, the branching cells and
//! the stored keys' finest cells, so the tree equals a fresh build over the same keys.

use crate::geom::deep::{common_level, morton_cmp};
use crate::geom::{DeepCell, DeepKey};
use smallvec::SmallVec;

/// "No node".
pub(crate) const NIL: u32 = u32::MAX;

/// One node; `head`/`tail` link a leaf's points (in a [`super::CompressedTree`]), `down` the same
/// cell one level lower (in a [`super::SkipQuadtree`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Node<const D: usize> {
    pub cell: DeepCell<D>,
    pub parent: u32,
    pub first_child: u32,
    pub next_sibling: u32,
    pub head: u32,
    pub tail: u32,
    pub down: u32,
}

/// The arena of a compressed quadtree; node 0 is the root cell, always present.
#[derive(Clone, Debug)]
pub(crate) struct Topology<const D: usize> {
    pub nodes: Vec<Node<D>>,
    free: Vec<u32>,
}

/// What [`Topology::insert`] did.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Inserted {
    /// The key's leaf.
    pub leaf: u32,
    /// `true` when the leaf is new (the key was not stored).
    pub created: bool,
    /// The branching node created above the new leaf, if any.
    pub branch: u32,
}

impl<const D: usize> Topology<D> {
    /// A tree holding no key: the root alone.
    pub fn new() -> Self {
        Topology {
            nodes: vec![Node::blank(DeepCell::root(), NIL)],
            free: Vec::new(),
        }
    }

    /// The number of nodes in use (the root included, 1 for an empty tree).
    pub fn len(&self) -> usize {
        self.nodes.len() - self.free.len()
    }

    /// `true` when no key is stored.
    pub fn is_empty(&self) -> bool {
        self.nodes[0].first_child == NIL
    }

    #[inline]
    pub fn node(&self, v: u32) -> &Node<D> {
        &self.nodes[v as usize]
    }

    #[inline]
    pub fn is_leaf(&self, v: u32) -> bool {
        self.nodes[v as usize].cell.level() == DeepCell::<D>::MAX_LEVEL
    }

    /// The children of `v`, in Morton order.
    #[inline]
    pub fn children(&self, v: u32) -> Children<'_, D> {
        Children {
            topology: self,
            at: self.nodes[v as usize].first_child,
        }
    }

    /// The child of `v` that holds `key`, if any; `v` must hold `key`.
    #[inline]
    pub fn child_holding(&self, v: u32, key: &DeepKey<D>) -> Option<u32> {
        self.children(v).find(|&c| self.node(c).cell.holds(key))
    }

    /// The deepest node holding `key` below `from` (which must hold it), calling `touch` on
    /// every node on the way, `from` included.
    #[inline]
    pub fn descend(&self, from: u32, key: &DeepKey<D>, mut touch: impl FnMut(u32)) -> u32 {
        let mut v = from;
        touch(v);
        while let Some(c) = self.child_holding(v, key) {
            v = c;
            touch(v);
        }
        v
    }

    fn alloc(&mut self, node: Node<D>) -> u32 {
        let Some(id) = self.free.pop() else {
            self.nodes.push(node);
            return (self.nodes.len() - 1) as u32;
        };
        self.nodes[id as usize] = node;
        id
    }

    fn release(&mut self, v: u32) {
        self.nodes[v as usize].parent = FREED;
        self.free.push(v);
    }

    /// Links the parentless `child` into `parent`'s list at its quadrant's place.
    fn link(&mut self, parent: u32, child: u32) {
        let cell = self.nodes[parent as usize].cell;
        let quadrant = |v: u32| cell.child_digit(&self.nodes[v as usize].cell.anchor());
        let q = quadrant(child);
        let mut prev = NIL;
        let mut at = self.nodes[parent as usize].first_child;
        while at != NIL && quadrant(at) < q {
            prev = at;
            at = self.nodes[at as usize].next_sibling;
        }
        self.nodes[child as usize].next_sibling = at;
        self.nodes[child as usize].parent = parent;
        self.set_next(parent, prev, child);
    }

    /// Makes `child` follow `prev` in `parent`'s list (the first child when `prev` is NIL).
    fn set_next(&mut self, parent: u32, prev: u32, child: u32) {
        if prev == NIL {
            self.nodes[parent as usize].first_child = child;
        } else {
            self.nodes[prev as usize].next_sibling = child;
        }
    }

    /// The sibling before `v` in its parent's list (NIL for the first child).
    fn previous(&self, v: u32) -> u32 {
        self.before(self.nodes[v as usize].parent, v)
    }

    /// The child of `parent` that `v` follows in its list: NIL when `v` is the first child, the
    /// last child when `v` is NIL.
    fn before(&self, parent: u32, v: u32) -> u32 {
        let mut prev = NIL;
        let mut at = self.nodes[parent as usize].first_child;
        while at != v {
            prev = at;
            at = self.nodes[at as usize].next_sibling;
        }
        prev
    }

    /// Puts `new` (parentless) where `old` is in `old`'s parent's list; `old` is left unlinked.
    fn replace(&mut self, old: u32, new: u32) {
        let parent = self.nodes[old as usize].parent;
        let prev = self.previous(old);
        self.nodes[new as usize].next_sibling = self.nodes[old as usize].next_sibling;
        self.nodes[new as usize].parent = parent;
        self.set_next(parent, prev, new);
    }

    /// Adds `key` below `at`, the deepest node holding it (from [`Topology::descend`]).
    pub fn insert(&mut self, at: u32, key: &DeepKey<D>) -> Inserted {
        let mut done = Inserted {
            leaf: at,
            created: false,
            branch: NIL,
        };
        if self.is_leaf(at) {
            return done;
        }
        let leaf = self.alloc(Node::blank(DeepCell::finest(*key), NIL));
        done.leaf = leaf;
        done.created = true;
        let cell = self.nodes[at as usize].cell;
        let q = cell.child_digit(key);
        let sibling = self
            .children(at)
            .find(|&c| cell.child_digit(&self.nodes[c as usize].cell.anchor()) == q);
        let Some(c) = sibling else {
            self.link(at, leaf);
            return done;
        };
        // `c` shares the quadrant but not the key: branch where they part.
        let l = common_level(&self.nodes[c as usize].cell.anchor(), key);
        let branch = self.alloc(Node::blank(DeepCell::of_key(key, l), NIL));
        self.replace(c, branch);
        self.nodes[c as usize].next_sibling = NIL;
        self.link(branch, c);
        self.link(branch, leaf);
        done.branch = branch;
        done
    }

    /// Removes the leaf `leaf` and, if its parent (not the root) is left with one child, splices
    /// the parent out; returns the spliced node or NIL.
    pub fn remove_leaf(&mut self, leaf: u32) -> u32 {
        let parent = self.nodes[leaf as usize].parent;
        let prev = self.previous(leaf);
        let next = self.nodes[leaf as usize].next_sibling;
        self.set_next(parent, prev, next);
        self.release(leaf);
        if parent == 0 {
            return NIL;
        }
        let only = self.nodes[parent as usize].first_child;
        if self.nodes[only as usize].next_sibling != NIL {
            return NIL;
        }
        self.replace(parent, only);
        self.release(parent);
        parent
    }

    /// The tree over distinct `keys` in increasing Morton order; `on_leaf(leaf, i)` is told the
    /// leaf of the `i`-th key.
    pub fn from_sorted(
        keys: impl IntoIterator<Item = DeepKey<D>>,
        mut on_leaf: impl FnMut(&mut Self, u32, usize),
    ) -> Self {
        let mut t = Self::new();
        // The rightmost path: every node on it is the last child of the one below it.
        let mut stack: Vec<u32> = vec![0];
        let mut previous: Option<DeepKey<D>> = None;
        for (i, key) in keys.into_iter().enumerate() {
            if let Some(p) = previous {
                debug_assert!(
                    morton_cmp(&p, &key).is_lt(),
                    "keys must be distinct and increasing"
                );
                let l = common_level(&p, &key);
                let mut popped = NIL;
                while let Some(&top) = stack.last() {
                    if t.nodes[top as usize].cell.level() <= l {
                        break;
                    }
                    popped = stack.pop().unwrap_or(NIL);
                }
                let top = *stack.last().unwrap_or(&0);
                if t.nodes[top as usize].cell.level() < l {
                    // The branching cell at l holds the popped subtree and the new key.
                    let branch = t.alloc(Node::blank(DeepCell::of_key(&key, l), NIL));
                    t.replace(popped, branch);
                    t.nodes[popped as usize].next_sibling = NIL;
                    t.nodes[popped as usize].parent = branch;
                    t.nodes[branch as usize].first_child = popped;
                    stack.push(branch);
                }
            }
            let parent = *stack.last().unwrap_or(&0);
            let leaf = t.alloc(Node::blank(DeepCell::finest(key), parent));
            t.append(parent, leaf);
            on_leaf(&mut t, leaf, i);
            stack.push(leaf);
            previous = Some(key);
        }
        t
    }

    /// Appends `child` as the last child of `parent` (the construction's order is Morton order).
    fn append(&mut self, parent: u32, child: u32) {
        self.set_next(parent, self.before(parent, NIL), child);
    }

    /// The nodes in pre-order (Morton order, an ancestor before its descendants), with an
    /// explicit stack.
    pub fn pre_order(&self) -> PreOrder<'_, D> {
        PreOrder {
            topology: self,
            stack: (!self.is_empty()).then_some(0).into_iter().collect(),
        }
    }

    /// Checks the arena; `Err` names the first broken rule: links agree, every child lies in
    /// its own quadrant strictly inside its parent and in Morton order, every internal node but
    /// the root branches, leaves are finest cells, the free list is disjoint
    /// from the tree.
    pub fn validate(&self) -> Result<(), String> {
        let root = self.node(0);
        if root.cell != DeepCell::root() || root.parent != NIL {
            return Err("node 0 is not the root cell".into());
        }
        let mut seen = 0usize;
        for v in self.pre_order() {
            seen += 1;
            let n = self.node(v);
            if self.is_leaf(v) {
                if n.first_child != NIL {
                    return Err(format!("leaf {v} has children"));
                }
                continue;
            }
            let mut count = 0;
            let mut last = None;
            for c in self.children(v) {
                count += 1;
                let cn = self.node(c);
                if cn.parent != v || cn.cell.level() <= n.cell.level() || !n.cell.contains(&cn.cell)
                {
                    return Err(format!("node {c} is not a proper child of node {v}"));
                }
                let q = n.cell.child_digit(&cn.cell.anchor());
                if last.is_some_and(|l| l >= q) {
                    return Err(format!(
                        "children of node {v} share a quadrant or are unsorted"
                    ));
                }
                last = Some(q);
            }
            if v != 0 && count < 2 {
                return Err(format!("node {v} does not branch ({count} child)"));
            }
        }
        if seen + self.free.len() != self.nodes.len() && !(self.is_empty() && seen == 0) {
            return Err(format!(
                "{seen} nodes reachable, {} free, {} slots",
                self.free.len(),
                self.nodes.len()
            ));
        }
        Ok(())
    }
}

/// Marks a node on the free list.
const FREED: u32 = NIL - 1;

impl<const D: usize> Node<D> {
    fn blank(cell: DeepCell<D>, parent: u32) -> Self {
        Node {
            cell,
            parent,
            first_child: NIL,
            next_sibling: NIL,
            head: NIL,
            tail: NIL,
            down: NIL,
        }
    }
}

/// The children of a node, in Morton order.
pub(crate) struct Children<'a, const D: usize> {
    topology: &'a Topology<D>,
    at: u32,
}

impl<const D: usize> Iterator for Children<'_, D> {
    type Item = u32;

    #[inline]
    fn next(&mut self) -> Option<u32> {
        (self.at != NIL).then(|| {
            let v = self.at;
            self.at = self.topology.nodes[v as usize].next_sibling;
            v
        })
    }
}

/// The nodes of a [`Topology`] in pre-order.
pub(crate) struct PreOrder<'a, const D: usize> {
    topology: &'a Topology<D>,
    stack: SmallVec<[u32; 64]>,
}

impl<const D: usize> Iterator for PreOrder<'_, D> {
    type Item = u32;

    fn next(&mut self) -> Option<u32> {
        let v = self.stack.pop()?;
        let at = self.stack.len();
        self.stack.extend(self.topology.children(v));
        self.stack[at..].reverse();
        Some(v)
    }
}
