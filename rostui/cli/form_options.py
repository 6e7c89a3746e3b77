"""What `rostui publish` and `rostui call` share: reading ``--form FILE`` before the app opens."""

from __future__ import annotations

from pathlib import Path
from typing import Optional

__all__ = ["checked_form"]


def checked_form(kind: str, path: Optional[Path]) -> Optional[Path]:
    """``path`` when it is a readable ``kind`` form or does not exist yet (ctrl+w will write it); otherwise one
    error line (``FILE:LINE: what``) and exit status 1."""
    if path is None or not path.exists():
        return path
    from rostui.cli.common import fail
    from rostui.models.message_form.form_file import FormFileError, apply_spec, read_form

    try:
        spec = read_form(path)
        if spec.kind != kind:
            raise FormFileError(f"{path}: a `{spec.kind}` form: open it with `rostui {spec.kind} --form {path}`")
        if kind == "publish":
            from rostui.models.message_form.rows import MessageForm
            from rostui.models.monitor.publish import PublishError, publish_class

            try:
                cls = publish_class(spec.type_name)
            except PublishError as exc:
                raise FormFileError(f"{path}: {exc}") from None
            apply_spec(MessageForm.of(cls), spec)
    except FormFileError as exc:
        fail(f"ERROR: {exc}")
    return path
