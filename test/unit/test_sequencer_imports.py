"""The sequencer's modules import each other without a cycle.

Every import counts, a function's own included (a cycle closed inside a
function still ties the modules together); importing a submodule counts
as importing the packages above it, except the module's own ancestors
(a package and the submodules it imports are one unit).
"""
import ast
import os

from pirate import paths

SOURCE = os.path.join(paths.PACKAGE_DIR, 'src')
PACKAGE = 'pirate.sequencer'


def module_files():
    """{module name: file} of every module below :data:`PACKAGE`."""
    found = {}
    for folder, _, names in os.walk(os.path.join(SOURCE, *PACKAGE.split('.'))):
        for name in names:
            if name.endswith('.py'):
                parts = os.path.relpath(os.path.join(folder, name), SOURCE)[:-3].split(os.sep)
                found['.'.join(parts[:-1] if parts[-1] == '__init__' else parts)] = os.path.join(folder, name)
    return found


def imported(tree):
    """Every module name ``tree`` imports, ``from a import b`` as both a and a.b."""
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                yield alias.name
        elif isinstance(node, ast.ImportFrom) and node.module and not node.level:
            yield node.module
            for alias in node.names:
                yield '%s.%s' % (node.module, alias.name)


def with_packages(name):
    """``name`` and the packages above it."""
    parts = name.split('.')
    return ['.'.join(parts[:i]) for i in range(1, len(parts) + 1)]


def graph():
    """{module: set of the sequencer modules it imports}."""
    files = module_files()
    edges = {}
    for module, path in files.items():
        with open(path) as stream:
            tree = ast.parse(stream.read(), path)
        ancestors = set(with_packages(module))
        edges[module] = {target for name in imported(tree) for target in with_packages(name)
                         if target in files and target not in ancestors}
    return edges


def cycle(edges):
    """One import cycle as a list of modules, or None."""
    state = {}

    def visit(module, path):
        state[module] = 'open'
        for target in sorted(edges[module]):
            if state.get(target) == 'open':
                return path[path.index(target):] + [target]
            if target not in state:
                found = visit(target, path + [target])
                if found:
                    return found
        state[module] = 'done'
        return None

    for module in sorted(edges):
        if module not in state:
            found = visit(module, [module])
            if found:
                return found
    return None


def test_the_sequencer_imports_without_a_cycle():
    found = cycle(graph())
    assert found is None, 'import cycle: %s' % ' -> '.join(found)


def test_a_cycle_is_found():
    edges = {'goals': {'pabs'}, 'pabs': {'pabs.junction'}, 'pabs.junction': {'junctions'}, 'junctions': {'goals'},
             'codes': set()}
    assert cycle(edges) == ['goals', 'pabs', 'pabs.junction', 'junctions', 'goals']
    edges['junctions'] = set()
    assert cycle(edges) is None
