"""Walking Blender shader node trees: the active output, and what really feeds an input socket
once reroutes, muted nodes and node groups are looked through."""

# Deeper than any real tree; a guard against a malformed one looping forever.
MAX_HOPS = 256


class Source:
    """What feeds an input socket: `node` and its output `socket`, or (node None) nothing, in
    which case `socket` is the input whose default_value applies. `stack` is the chain of Group
    nodes the walk entered to reach `node` (needed to leave the group through its inputs)."""

    __slots__ = ("node", "socket", "stack")

    def __init__(self, node, socket, stack):
        self.node = node
        self.socket = socket
        self.stack = stack

    @property
    def output_name(self):
        return self.socket.name if self.node is not None else None


def output_node(node_tree, output_type):
    """The output node Cycles renders: the active one targeting ALL or CYCLES."""
    outputs = [n for n in node_tree.nodes
               if n.type == output_type and getattr(n, "target", 'ALL') in {'ALL', 'CYCLES'}]
    for node in outputs:
        if getattr(node, "is_active_output", False):
            return node
    return outputs[0] if outputs else None


def node_path(node, stack):
    """A node's name as the artist finds it: 'Group Node/Inner Node' inside groups."""
    return "/".join([group.name for group in stack] + [node.name])


def _counts(link):
    # A muted or invalid (red) link leaves the input unlinked, as in Cycles.
    return not getattr(link, "is_muted", False) and getattr(link, "is_valid", True)


class LinkIndex:
    """The active link into each input socket, from one pass over each node tree's links.

    NodeSocket.links scans every link of the tree on each call (Blender's bpy_types.py says
    O(len(nodetree.links))), so asking it once per socket made walking a large tree quadratic.
    Keep one index per material conversion: it is not updated when the tree changes."""

    def __init__(self):
        self._trees = {}

    def link_to(self, socket):
        if socket is None or not socket.is_linked:
            return None
        tree = socket.id_data
        index = self._trees.get(tree)
        if index is None:
            index = {}
            for link in tree.links:
                if _counts(link):
                    index.setdefault(link.to_socket, link)  # the first, as socket.links
            self._trees[tree] = index
        return index.get(socket)


def _active_link(socket):
    if socket is None or not socket.is_linked:
        return None
    for link in socket.links:
        if _counts(link):
            return link
    return None


def _by_identifier(sockets, identifier, index):
    for socket in sockets:
        if socket.identifier == identifier:
            return socket
    return sockets[index] if 0 <= index < len(sockets) else None


def _socket_index(sockets, socket):
    for i, s in enumerate(sockets):
        if s == socket:
            return i
    return -1


def _group_output(tree):
    outputs = [n for n in tree.nodes if n.type == 'GROUP_OUTPUT']
    for node in outputs:
        if getattr(node, "is_active_output", False):
            return node
    return outputs[0] if outputs else None


def source(socket, stack=(), links=None):
    """The Source feeding input `socket` (of a node reached through `stack`); `links` is a
    LinkIndex (without one each socket's links are searched, fine for a handful of calls)."""
    for _ in range(MAX_HOPS):
        link = links.link_to(socket) if links is not None else _active_link(socket)
        if link is None:
            return Source(None, socket, stack)
        node, out = link.from_node, link.from_socket
        if node.mute:
            # A muted node passes its matching input straight through (or gives nothing).
            through = [l.from_socket for l in node.internal_links if l.to_socket == out]
            if not through:
                return Source(None, socket, stack)
            socket = through[0]
        elif node.type == 'REROUTE':
            socket = node.inputs[0]
        elif node.type == 'GROUP':
            tree = node.node_tree
            group_out = _group_output(tree) if tree is not None else None
            inner = None
            if group_out is not None:
                inner = _by_identifier(group_out.inputs, out.identifier,
                                       _socket_index(node.outputs, out))
            if inner is None:
                return Source(None, socket, stack)
            stack = stack + (node,)
            socket = inner
        elif node.type == 'GROUP_INPUT':
            if not stack:
                return Source(None, socket, stack)
            group = stack[-1]
            outer = _by_identifier(group.inputs, out.identifier, _socket_index(node.outputs, out))
            if outer is None:
                return Source(None, socket, stack)
            stack = stack[:-1]
            socket = outer
        else:
            return Source(node, out, stack)
    return Source(None, socket, stack)


def find_input(node, *names):
    """First input socket with one of `names` (Blender renames sockets between versions)."""
    for name in names:
        socket = node.inputs.get(name)
        if socket is not None:
            return socket
    return None
