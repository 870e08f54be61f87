"""Checks a JSON value against a JSON Schema printed by `glintlab schema FILE`.

Only the keywords glintlab's schemas use are understood (type, enum, properties, required,
additionalProperties, items, and the annotations $schema, title, description); a schema with any
other keyword is refused, so a schema that grows a rule this checker would ignore fails loudly
instead of passing everything.
"""

ANNOTATIONS = {"$schema", "title", "description"}
RULES = {"type", "enum", "properties", "required", "additionalProperties", "items"}

JSON_TYPES = {
    "object": lambda v: isinstance(v, dict),
    "array": lambda v: isinstance(v, list),
    "string": lambda v: isinstance(v, str),
    "boolean": lambda v: isinstance(v, bool),
    "integer": lambda v: isinstance(v, int) and not isinstance(v, bool),
    "number": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
    "null": lambda v: v is None,
}


class SchemaError(Exception):
    """The value does not follow the schema; the message names where and why."""


def type_name(value):
    for name in ("null", "boolean", "integer", "number", "string", "array", "object"):
        if JSON_TYPES[name](value):
            return name
    return type(value).__name__


def check_schema(schema, where="schema"):
    """Refuses a schema using a keyword this checker does not implement."""
    if not isinstance(schema, dict):
        raise ValueError(f"{where} is not an object")
    unknown = sorted(set(schema) - ANNOTATIONS - RULES)
    if unknown:
        raise ValueError(f"{where} uses {', '.join(unknown)}, which this checker does not "
                         "implement")
    for key, sub in schema.get("properties", {}).items():
        check_schema(sub, f"{where}.properties.{key}")
    if "items" in schema:
        check_schema(schema["items"], f"{where}.items")


def validate(value, schema, where):
    """Raises SchemaError naming `where` (e.g. 'entry 3 (fixture.fails) "p_value"') and the rule
    broken; returns None when `value` follows `schema`."""
    if "type" in schema:
        allowed = schema["type"] if isinstance(schema["type"], list) else [schema["type"]]
        if not any(JSON_TYPES[t](value) for t in allowed):
            raise SchemaError(f"{where} is {type_name(value)} {value!r:.40}, the schema wants "
                              f"{' or '.join(allowed)}")
    if "enum" in schema and value not in schema["enum"]:
        valid = ", ".join("null" if v is None else str(v) for v in schema["enum"])
        raise SchemaError(f"{where} is {value!r:.40} (valid: {valid})")
    if isinstance(value, dict):
        properties = schema.get("properties", {})
        missing = [k for k in schema.get("required", []) if k not in value]
        if missing:
            raise SchemaError(f"{where} lacks {', '.join(missing)}")
        if schema.get("additionalProperties", True) is False:
            extra = sorted(k for k in value if k not in properties)
            if extra:
                raise SchemaError(f"{where} has {', '.join(extra)}, which the schema does not "
                                  "name")
        for key, sub in properties.items():
            if key in value:
                validate(value[key], sub, f"{where} \"{key}\"")
    if isinstance(value, list) and "items" in schema:
        for i, item in enumerate(value):
            validate(item, schema["items"], f"{where}[{i}]")
