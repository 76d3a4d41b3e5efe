"""LLM layer: chat client and cache, prompts, grounding, translation, guidance, offline backends."""
