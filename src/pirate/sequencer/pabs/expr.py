"""Guards of a PAB's transition table, written once as expressions.

A guard is an expression over the PAB's facts (the namedtuple its
``facts`` method reads after every action); the same tree gives the test
the state machine runs and the text the table prints::

    START = all_of(TURN, FRONT, REAR, STRAIGHT, not_(IN_A_CORNER))

- :func:`fact`: a boolean field of the facts (``fact('found', 'junction sensed')``);
- :func:`equals`: a field that holds one value (``equals('rear', 'full')``: "rear full");
- :func:`all_of`, :func:`any_of`, :func:`not_`: AND, OR, NOT;
- :func:`named`: a sub-expression printed by its name, defined once
  (:func:`definitions` lists it under the table);
- :data:`ALWAYS`: the guard that always holds, printed "-".

Pure Python.
"""
import collections


class Expr(object):
    """A guard: ``test(facts)`` and ``text`` from the same expression."""

    #: Binding strength when printed inside another expression (higher binds tighter).
    precedence = 3

    def test(self, facts):
        """True when the guard holds for ``facts``."""
        raise NotImplementedError

    @property
    def text(self):
        """The guard as the table prints it."""
        raise NotImplementedError

    def children(self):
        """The sub-expressions (none for a fact)."""
        return ()

    def inside(self, outer):
        """The text, parenthesised when it binds looser than ``outer``."""
        return '(%s)' % self.text if self.precedence < outer else self.text

    def __repr__(self):
        return '<guard %s>' % self.text


class Fact(Expr):
    """A boolean field of the facts; ``text`` names it in the table, ``means`` says what it is."""

    def __init__(self, field, text=None, means=''):
        self.field, self._text, self.means = field, text or field, means

    def test(self, facts):
        return bool(getattr(facts, self.field))

    @property
    def text(self):
        return self._text


class Equals(Fact):
    """A field that holds one value, printed "<field> <value>"."""

    def __init__(self, field, value, text=None, means=''):
        Fact.__init__(self, field, text or '%s %s' % (field, value), means)
        self.value = value

    def test(self, facts):
        return getattr(facts, self.field) == self.value


class Not(Expr):
    """NOT its operand."""

    def __init__(self, operand):
        self.operand = operand

    def test(self, facts):
        return not self.operand.test(facts)

    @property
    def text(self):
        return 'NOT %s' % self.operand.inside(3)

    def children(self):
        return (self.operand,)


class _Joined(Expr):
    """Operands joined by one keyword."""

    keyword, combine, operand_precedence = None, None, 3

    def __init__(self, operands):
        if len(operands) < 2:
            raise ValueError('%s needs at least two operands, got %d' % (self.keyword, len(operands)))
        self.operands = tuple(operands)

    def test(self, facts):
        return self.combine(operand.test(facts) for operand in self.operands)

    @property
    def text(self):
        return (' %s ' % self.keyword).join(operand.inside(self.operand_precedence) for operand in self.operands)

    def children(self):
        return self.operands


class AllOf(_Joined):
    """Every operand holds (AND)."""

    keyword, combine, precedence = 'AND', all, 2


class AnyOf(_Joined):
    """Some operand holds (OR)."""

    keyword, combine, precedence = 'OR', any, 1
    #: AND inside OR is parenthesised too: "a OR (b AND c)" reads unambiguously.


class Named(Expr):
    """An expression printed by its name; :func:`definitions` spells it out."""

    def __init__(self, name, body, means=''):
        self.name, self.body, self.means = name, body, means

    def test(self, facts):
        return self.body.test(facts)

    @property
    def text(self):
        return self.name

    def children(self):
        return (self.body,)


class _Always(Expr):
    def test(self, facts):
        return True

    @property
    def text(self):
        return '-'


#: The guard of a transition taken whatever the facts.
ALWAYS = _Always()


def fact(field, text=None, means=''):
    """The boolean fact ``field``, printed ``text`` (default: the field's name)."""
    return Fact(field, text, means)


def equals(field, value, text=None, means=''):
    """True when fact ``field`` is ``value``."""
    return Equals(field, value, text, means)


def not_(operand):
    """NOT ``operand``."""
    return Not(operand)


def all_of(*operands):
    """``operands`` joined by AND."""
    return AllOf(operands)


def any_of(*operands):
    """``operands`` joined by OR."""
    return AnyOf(operands)


def named(name, body, means=''):
    """``body``, printed as ``name``."""
    return Named(name, body, means)


def walk(expr):
    """``expr`` and every sub-expression in it, depth first, outer first."""
    yield expr
    for child in expr.children():
        for inner in walk(child):
            yield inner


def fields(expr):
    """The facts' field names ``expr`` reads."""
    return {node.field for node in walk(expr) if isinstance(node, Fact)}


def definitions(guards):
    """The named expressions in ``guards`` (inner names too), first use first,
    each once: an OrderedDict name -> :class:`Named`."""
    found = collections.OrderedDict()
    for guard in guards:
        for node in walk(guard):
            if isinstance(node, Named):
                found.setdefault(node.name, node)
    return found


def facts_read(guards):
    """The facts (:class:`Fact`) ``guards`` read, first use first, each text once."""
    found = collections.OrderedDict()
    for guard in guards:
        for node in walk(guard):
            if isinstance(node, Fact):
                found.setdefault(node.text, node)
    return found
