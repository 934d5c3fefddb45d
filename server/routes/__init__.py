"""Thin routes: validate, convert, call one solver function, convert back."""
